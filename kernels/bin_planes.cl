/* RANSAC plane scoring of the bin fit (host/detect/bin/bin_planes.cpp): for each candidate plane,
 * the number of sample points within tol of it. One work item per plane scans every point, so
 * the counts are exact integers whatever the scheduling. The points come as three arrays (x, y,
 * z) so that a work item takes eight at a time in vector registers; each lane rounds exactly as
 * bp_plane_distance does (the same products and sums in the same order, not contracted). */
#pragma OPENCL FP_CONTRACT OFF
#include "scene_mask_shared.h"

__kernel void bin_plane_inliers(__global const float* xs, __global const float* ys,
                                __global const float* zs, const uint n,
                                __global const bp_plane* planes, const uint count,
                                const float tol, __global uint* inliers) {
  const uint k = get_global_id(0);
  if (k >= count) return;
  const bp_plane pl = planes[k];
  const float8 nx = (float8)(pl.nx), ny = (float8)(pl.ny), nz = (float8)(pl.nz);
  const float8 d = (float8)(pl.d), tol8 = (float8)(tol);
  int8 lanes = (int8)(0);
  const uint blocks = n / 8;
  for (uint b = 0; b < blocks; ++b) {
    const float8 x = vload8(b, xs), y = vload8(b, ys), z = vload8(b, zs);
    const float8 s = nx * x + ny * y + nz * z + d;
    lanes -= fabs(s) <= tol8; /* a true vector comparison is -1 */
  }
  uint c = (uint)(lanes.s0 + lanes.s1 + lanes.s2 + lanes.s3 + lanes.s4 + lanes.s5 + lanes.s6 +
                  lanes.s7);
  for (uint i = 8 * blocks; i < n; ++i) c += bp_plane_distance(&pl, xs[i], ys[i], zs[i]) <= tol ? 1u : 0u;
  inliers[k] = c;
}

/* The sample grid of the bin fit (sample_points in host/detect/bin/bin_planes.cpp): work item g
 * copies the point of grid cell (g % grid_w, g / grid_w), pixel (stride * that), so that only
 * the grid, not the whole point image, is read back; the host keeps the ones with data, in the
 * grid's row-major order. */
__kernel void bin_sample_grid(__global const float4* points, const uint width,
                              const uint stride, const uint grid_w, const uint cells,
                              __global float4* out) {
  const uint g = get_global_id(0);
  if (g >= cells) return;
  out[g] = points[(g / grid_w) * stride * width + (g % grid_w) * stride];
}
