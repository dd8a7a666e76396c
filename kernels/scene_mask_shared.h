/* The "may be used" region of a scene (--roi, --bin): up to two boxes, each in its own frame
 * (a rotation and an origin in the camera frame). A pixel may be used when it has data and its
 * point lies inside every active box. Shared by kernels/scene_mask.cl and its C++ reference
 * (host/detect/bin/scene_mask.cpp) so that both evaluate the same float operations in the same
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

/* The bin's walls, for points the sensor sees through one (a wire-mesh basket's, between its
 * bars): in the frame of the bin box (bin.r, bin.t: origin at the floor's centre, z up), the
 * inner faces at x = +-reach[0] and y = +-reach[1] from the floor (z = 0) to the rim (z =
 * height). sides: bit 0 the wall at +x, 1 at -x, 2 at +y, 3 at -y (a wall the bin fit did not see
 * is not tested: its place is a guess); 0: no test. cam: the camera's centre in that frame. */
typedef struct {
  float reach[2];
  float height;
  bp_u32 sides;
  float cam[3];
  bp_u32 reserved;
} bp_walls;

typedef struct {
  bp_box roi; /* --roi, already in the camera frame's terms */
  bp_box bin; /* the bin's interior shrunk by the margin */
  bp_walls walls; /* with bin active: points seen through these walls are not kept */
} bp_region;

/* Coordinate a of the point p (camera frame, already less the box's origin: d = p - t) in the
 * box's frame. */
BP_FN float bp_box_coord(const bp_box* b, int a, float dx, float dy, float dz) {
  return b->r[3 * a] * dx + b->r[3 * a + 1] * dy + b->r[3 * a + 2] * dz;
}

BP_FN int bp_box_keeps(const bp_box* b, float x, float y, float z) {
  if (!b->active) return 1;
  const float dx = x - b->t[0], dy = y - b->t[1], dz = z - b->t[2];
  for (int a = 0; a < 3; ++a) {
    const float q = bp_box_coord(b, a, dx, dy, dz);
    if (!(q >= b->lo[a] && q <= b->hi[a])) return 0;
  }
  return 1;
}

/* 1 when the segment from the camera c to the point q (both in the bin's frame) crosses the
 * plane of coordinate `axis` = at (the other horizontal coordinate within +-span) between the
 * floor and the rim, before reaching q. Without a division: the crossing lies at s = a / b of
 * the segment (a = at - c, b = q - c on that axis, the same sign when it crosses), so its
 * coordinates times |b| are compared with the bounds times |b|. */
BP_FN int bp_segment_crosses_wall(const float c[3], const float q[3], int axis, float at,
                                  float span, float height) {
  const float a = at - c[axis], b = q[axis] - c[axis];
  if (!((a > 0.0f && b >= a) || (a < 0.0f && b <= a))) return 0;
  const float ab = a < 0.0f ? -a : a, bb = b < 0.0f ? -b : b;
  const int other = 1 - axis;
  const float o = c[other] * bb + ab * (q[other] - c[other]);
  const float h = c[2] * bb + ab * (q[2] - c[2]);
  const float ob = span * bb;
  return o >= -ob && o <= ob && h >= 0.0f && h <= height * bb;
}

/* 1 when the point (camera frame) is seen through one of the walls tested. */
BP_FN int bp_seen_through_walls(const bp_box* bin, const bp_walls* w, float x, float y, float z) {
  if (!bin->active || w->sides == 0u) return 0;
  const float dx = x - bin->t[0], dy = y - bin->t[1], dz = z - bin->t[2];
  float q[3];
  for (int a = 0; a < 3; ++a) q[a] = bp_box_coord(bin, a, dx, dy, dz);
  for (int k = 0; k < 4; ++k) {
    if (!(w->sides & (1u << k))) continue;
    const int axis = k / 2;
    const float at = (k % 2 == 0) ? w->reach[axis] : -w->reach[axis];
    if (bp_segment_crosses_wall(w->cam, q, axis, at, w->reach[1 - axis], w->height)) return 1;
  }
  return 0;
}

/* 1 when the point (w != 0: it has data) may be used. */
BP_FN unsigned char bp_region_keeps(const bp_region* g, float x, float y, float z, float w) {
  if (w == 0.0f) return 0;
  return (unsigned char)(bp_box_keeps(&g->roi, x, y, z) && bp_box_keeps(&g->bin, x, y, z) &&
                         !bp_seen_through_walls(&g->bin, &g->walls, x, y, z));
}

/* What reaches into the bin over its rim from outside (a robot arm, a hose, a part hanging over
 * the rim): standing higher than the rim, it is the highest thing inside the interior's box
 * without being in the bin. A pixel's class, in the bin's frame (q = r (p - t), origin the
 * floor's centre, z up): no data; not over the rim (q.z <= lift: the rim, the pile, the floor,
 * the ground); over the rim inside the footprint |q.x| <= reach[0], |q.y| <= reach[1]; or over
 * the rim beyond a side of the footprint the bin fit saw (sides: bit 0 +x, 1 -x, 2 +y, 3 -y),
 * where nothing the bin holds can be. host/detect/bin/over_rim.hpp grows the last class into the
 * pixels over the rim it is joined to. */
#define BP_OVER_RIM_NO 0u     /* has data, not over the rim */
#define BP_OVER_RIM_IN 1u     /* over the rim, over the bin's footprint */
#define BP_OVER_RIM_OUT 2u    /* over the rim, beyond a side seen */
#define BP_OVER_RIM_NODATA 3u /* no depth */

typedef struct {
  float r[9]; /* rows: the bin's axes in camera coordinates */
  float t[3]; /* the floor's centre, camera frame (mm) */
  float reach[2]; /* the footprint's half-sizes, W / 2 and D / 2 grown by the clearance (mm) */
  float lift;     /* the rim's height over the floor plus the clearance (mm) */
  bp_u32 sides;   /* the sides whose beyond seeds (the sides the bin fit saw) */
} bp_over_rim;

/* The class of a point (w = 0: no data); *height = its height in the bin's frame. A NaN point
 * is not over the rim (the comparisons fail). */
BP_FN bp_u32 bp_over_rim_class(const bp_over_rim* g, float x, float y, float z, float w,
                               float* height) {
  *height = 0.0f;
  if (w == 0.0f) return BP_OVER_RIM_NODATA;
  const float dx = x - g->t[0], dy = y - g->t[1], dz = z - g->t[2];
  const float qx = g->r[0] * dx + g->r[1] * dy + g->r[2] * dz;
  const float qy = g->r[3] * dx + g->r[4] * dy + g->r[5] * dz;
  const float qz = g->r[6] * dx + g->r[7] * dy + g->r[8] * dz;
  *height = qz;
  if (!(qz > g->lift)) return BP_OVER_RIM_NO;
  const bp_u32 beyond = (qx > g->reach[0] ? 1u : 0u) | (qx < -g->reach[0] ? 2u : 0u) |
                        (qy > g->reach[1] ? 4u : 0u) | (qy < -g->reach[1] ? 8u : 0u);
  return (beyond & g->sides) ? BP_OVER_RIM_OUT : BP_OVER_RIM_IN;
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
