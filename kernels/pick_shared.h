/* The gripper-clearance test of pick planning (host/detect/pick/pick_clearance.hpp), shared by
 * the OpenCL C kernel (kernels/pick_clearance.cl) and its C++ reference, so that both compute
 * the same distances with the same float operations in the same order.
 * Valid OpenCL C 1.2 and valid C++20; structs hold only 4-byte scalars. */
#ifndef BINPICK_PICK_SHARED_H
#define BINPICK_PICK_SHARED_H

#include "binpick_shared.h"

#ifdef __OPENCL_VERSION__
#define BP_PICK_SQRT sqrt
#define BP_PICK_FABS fabs
#else
#define BP_PICK_SQRT std::sqrt
#define BP_PICK_FABS std::fabs
#endif

#define BP_PICK_MAX_SOLIDS 3
#define BP_PICK_BOX 0u
#define BP_PICK_CYLINDER 1u

/* One gripper at one grasp: the camera frame into the grasp's (q = rot (p - origin), rot row-major:
 * z the approach, into the part), its solids in that frame (a box's half extents, or a cylinder
 * along z: radius extent[0], half length extent[2]), and the pixels that can hold a point near it. */
typedef struct {
  float rot[9];
  float origin[3];
  bp_u32 shape[BP_PICK_MAX_SOLIDS];
  float centre[3 * BP_PICK_MAX_SOLIDS];
  float extent[3 * BP_PICK_MAX_SOLIDS];
  bp_u32 solids;
  bp_u32 rect[4]; /* x0, y0, x1, y1: columns [x0, x1), rows [y0, y1) */
  float tolerance; /* a point deeper than this inside a solid collides (mm) */
  float cap;       /* clearances beyond this are not told apart (mm) */
} bp_pick_candidate;

/* What the points of a candidate's window say: how many lie inside the gripper deeper than the
 * tolerance, and the least distance to it of those on the gripper's side of the grasp point
 * (q.z < -tolerance: the part's own face under a cup is not an obstacle), at most cap. */
typedef struct {
  bp_u32 colliding;
  float clearance;
} bp_pick_result;

/* Signed distance from q (grasp frame) to solid k: negative inside. */
BP_FN float bp_pick_solid_distance(const bp_pick_candidate* c, bp_u32 k, float qx, float qy, float qz) {
  const float dx = qx - c->centre[3 * k], dy = qy - c->centre[3 * k + 1],
              dz = qz - c->centre[3 * k + 2];
  float a, b, e;
  if (c->shape[k] == BP_PICK_CYLINDER) {
    a = BP_PICK_SQRT(dx * dx + dy * dy) - c->extent[3 * k];
    b = BP_PICK_FABS(dz) - c->extent[3 * k + 2];
    e = -1e30f;
  } else {
    a = BP_PICK_FABS(dx) - c->extent[3 * k];
    b = BP_PICK_FABS(dy) - c->extent[3 * k + 1];
    e = BP_PICK_FABS(dz) - c->extent[3 * k + 2];
  }
  const float oa = a > 0.0f ? a : 0.0f, ob = b > 0.0f ? b : 0.0f, oe = e > 0.0f ? e : 0.0f;
  const float outside = BP_PICK_SQRT(oa * oa + ob * ob + oe * oe);
  if (outside > 0.0f) return outside;
  float inside = a > b ? a : b;
  return inside > e ? inside : e;
}

/* The gripper's signed distance at camera-frame point (px, py, pz); qz gets the grasp frame's z. */
BP_FN float bp_pick_distance(const bp_pick_candidate* c, float px, float py, float pz, float* qz) {
  const float x = px - c->origin[0], y = py - c->origin[1], z = pz - c->origin[2];
  const float gx = c->rot[0] * x + c->rot[1] * y + c->rot[2] * z;
  const float gy = c->rot[3] * x + c->rot[4] * y + c->rot[5] * z;
  const float gz = c->rot[6] * x + c->rot[7] * y + c->rot[8] * z;
  *qz = gz;
  float best = 1e30f;
  for (bp_u32 k = 0; k < c->solids; ++k) {
    const float d = bp_pick_solid_distance(c, k, gx, gy, gz);
    best = d < best ? d : best;
  }
  return best;
}

#endif
