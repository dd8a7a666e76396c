/* The "may be used" region of a scene (--roi, --bin): up to two boxes, each in its own frame
 * (a rotation and an origin in the camera frame). A pixel may be used when it has data and its
 * point lies inside every active box. Shared by kernels/scene_mask.cl and its C++ reference
 * (host/detect/scene_mask.cpp) so that both evaluate the same float operations in the same
 * order: the masks compare exactly. Valid OpenCL C 1.2 and valid C++20; 4-byte scalars only. */
#ifndef BINPICK_SCENE_MASK_SHARED_H
#define BINPICK_SCENE_MASK_SHARED_H

#include "binpick_shared.h"

/* A box: q = r (p - t), kept when lo <= q <= hi on every axis (bounds included). r holds the
 * box frame's axes in camera coordinates as rows, t the frame's origin in the camera frame. */
typedef struct {
  float r[9];
  float t[3];
  float lo[3];
  float hi[3];
  bp_u32 active; /* 0: the box keeps every point */
  bp_u32 reserved[3];
} bp_box;

typedef struct {
  bp_box roi; /* --roi, already in the camera frame's terms */
  bp_box bin; /* the bin's interior shrunk by the margin */
} bp_region;

BP_FN int bp_box_keeps(const bp_box* b, float x, float y, float z) {
  if (!b->active) return 1;
  const float dx = x - b->t[0], dy = y - b->t[1], dz = z - b->t[2];
  for (int a = 0; a < 3; ++a) {
    const float q = b->r[3 * a] * dx + b->r[3 * a + 1] * dy + b->r[3 * a + 2] * dz;
    if (!(q >= b->lo[a] && q <= b->hi[a])) return 0;
  }
  return 1;
}

/* 1 when the point (w != 0: it has data) may be used. */
BP_FN unsigned char bp_region_keeps(const bp_region* g, float x, float y, float z, float w) {
  if (w == 0.0f) return 0;
  return (unsigned char)(bp_box_keeps(&g->roi, x, y, z) && bp_box_keeps(&g->bin, x, y, z));
}

/* Plane scoring of the bin fit (kernels/bin_planes.cl): a plane n . p + d = 0 with unit n.
 * A point is an inlier when |n . p + d| <= tol. */
typedef struct {
  float nx, ny, nz, d;
} bp_plane;

BP_FN float bp_plane_distance(const bp_plane* pl, float x, float y, float z) {
  const float s = pl->nx * x + pl->ny * y + pl->nz * z + pl->d;
  return s < 0.0f ? -s : s;
}

#endif /* BINPICK_SCENE_MASK_SHARED_H */
