/* Per-pixel normals of an organised point image (float4 xyzw, w = 1 where there is data): the
 * least-squares plane through the valid points of a (2r+1)^2 window, i.e. the eigenvector of
 * the smallest eigenvalue of their covariance, oriented towards the camera (n . p < 0).
 * Neighbours farther than max_distance from the centre point are ignored, so a normal does not
 * bleed across a depth discontinuity (the border between two parts). Out: float4 (n, 1), or
 * all 0 where the centre has no data, fewer than 3 neighbours count, or the fit is degenerate. */
#pragma OPENCL FP_CONTRACT OFF
#include "scene_shared.h"

/* The normal of pixel i. In the kernels specialised for a radius of 1, 2 or 3 the radius is a
 * constant, so the window loops unroll into straight-line, branch-free code that PoCL
 * vectorises across work items (about 10 times faster than the generic loop on a CPU). Pixels
 * outside the image or rejected add exact zeros, so every variant sums the same values in the
 * same (row-major) order and gives the same result. */
static inline float4 normal_at(__global const float4* points, const uint width,
                               const uint height, const uint i, int radius,
                               float max_distance, const float metric_radius,
                               const float focal) {
  const float4 c = points[i];
  if (c.w == 0.0f) return (float4)(0.0f, 0.0f, 0.0f, 0.0f);
  const int u = (int)(i % width), v = (int)(i / width);
  int step = 1;
  if (metric_radius > 0.0f) {
    bp_metric_window(c.z, metric_radius, focal, &radius, &step);
    max_distance = fmin(max_distance, metric_radius);
  }
  const float max2 = max_distance * max_distance;
  /* Coordinates relative to the centre point: small numbers, so the one-pass covariance
   * sum(q q^T)/n - m m^T loses nothing to cancellation at a depth of a metre. */
  float n = 0.0f, sx = 0.0f, sy = 0.0f, sz = 0.0f;
  float sxx = 0.0f, sxy = 0.0f, sxz = 0.0f, syy = 0.0f, syz = 0.0f, szz = 0.0f;
  for (int dy = -radius; dy <= radius; dy += step) {
    const int y = clamp(v + dy, 0, (int)height - 1);
    for (int dx = -radius; dx <= radius; dx += step) {
      const int x = clamp(u + dx, 0, (int)width - 1);
      const float4 p = points[y * (int)width + x];
      const bool use = y == v + dy && x == u + dx && p.w != 0.0f &&
                       bp_dist2(p.x, p.y, p.z, c.x, c.y, c.z) <= max2;
      const float wgt = use ? 1.0f : 0.0f;
      const float qx = (p.x - c.x) * wgt, qy = (p.y - c.y) * wgt, qz = (p.z - c.z) * wgt;
      n += wgt;
      sx += qx; sy += qy; sz += qz;
      sxx += qx * qx; sxy += qx * qy; sxz += qx * qz;
      syy += qy * qy; syz += qy * qz; szz += qz * qz;
    }
  }
  if (n < 3.0f) return (float4)(0.0f, 0.0f, 0.0f, 0.0f);
  const float mx = sx / n, my = sy / n, mz = sz / n;
  float a[9], e[9];
  a[0] = sxx / n - mx * mx; a[1] = sxy / n - mx * my; a[2] = sxz / n - mx * mz;
  a[4] = syy / n - my * my; a[5] = syz / n - my * mz; a[8] = szz / n - mz * mz;
  a[3] = a[1]; a[6] = a[2]; a[7] = a[5];
  bp_sym3_jacobi(a, e);
  /* Order the eigenvalues: smallest gives the normal, middle vs largest the degeneracy. */
  int lo = 0, hi = 0;
  for (int k = 1; k < 3; ++k) {
    if (a[4 * k] < a[4 * lo]) lo = k;
    if (a[4 * k] >= a[4 * hi]) hi = k;
  }
  if (lo == hi) return (float4)(0.0f, 0.0f, 0.0f, 0.0f); /* only with NaN */
  const int mid = 3 - lo - hi;
  if (!(a[4 * mid] > BP_NORMAL_DEGENERATE_RATIO * a[4 * hi]))
    return (float4)(0.0f, 0.0f, 0.0f, 0.0f);
  float nx = e[lo], ny = e[3 + lo], nz = e[6 + lo];
  const float len = sqrt(nx * nx + ny * ny + nz * nz);
  if (!(len > 0.0f)) return (float4)(0.0f, 0.0f, 0.0f, 0.0f);
  nx /= len; ny /= len; nz /= len;
  if (nx * c.x + ny * c.y + nz * c.z > 0.0f) {
    nx = -nx; ny = -ny; nz = -nz;
  }
  return (float4)(nx, ny, nz, 1.0f);
}

/* Any radius; with metric_radius > 0 (mm) the window follows from it and the pixel's depth
 * (bp_metric_window; focal in pixels) instead of `radius`, and neighbours lie within the smaller
 * of metric_radius and max_distance. */
__kernel void normals_from_points(__global const float4* points, const uint width,
                                  const uint height, const int radius, const float max_distance,
                                  const float metric_radius, const float focal,
                                  __global float4* normals) {
  const uint i = get_global_id(0);
  if (i >= width * height) return;
  normals[i] = normal_at(points, width, height, i, radius, max_distance, metric_radius, focal);
}

/* The common pixel radii, with the radius a constant (same arguments; `radius`, metric_radius
 * and focal are ignored). */
#define BP_NORMALS_FIXED(R)                                                                   \
  __kernel void normals_from_points_r##R(__global const float4* points, const uint width,    \
                                         const uint height, const int radius,                \
                                         const float max_distance, const float metric_radius, \
                                         const float focal, __global float4* normals) {      \
    const uint i = get_global_id(0);                                                          \
    if (i >= width * height) return;                                                          \
    normals[i] = normal_at(points, width, height, i, R, max_distance, 0.0f, 0.0f);            \
  }
BP_NORMALS_FIXED(1)
BP_NORMALS_FIXED(2)
BP_NORMALS_FIXED(3)

/* Normals of a list of pixels only (the points the detector keeps after cropping and
 * subsampling a hypothesis' neighbourhood: a few thousand of the image's 1.4 M). normals[j] is
 * the normal of pixel pixels[j], computed by the same normal_at on the full point image, so it
 * equals the full-image kernel's value at that pixel. */
__kernel void normals_at_pixels(__global const float4* points, const uint width,
                                const uint height, const int radius, const float max_distance,
                                const float metric_radius, const float focal,
                                __global const uint* pixels, const uint count,
                                __global float4* normals) {
  const uint j = get_global_id(0);
  if (j >= count) return;
  normals[j] = normal_at(points, width, height, pixels[j], radius, max_distance, metric_radius,
                         focal);
}

#define BP_NORMALS_AT_PIXELS_FIXED(R)                                                         \
  __kernel void normals_at_pixels_r##R(__global const float4* points, const uint width,      \
                                       const uint height, const int radius,                  \
                                       const float max_distance, const float metric_radius,  \
                                       const float focal, __global const uint* pixels,       \
                                       const uint count, __global float4* normals) {         \
    const uint j = get_global_id(0);                                                          \
    if (j >= count) return;                                                                   \
    normals[j] = normal_at(points, width, height, pixels[j], R, max_distance, 0.0f, 0.0f);    \
  }
BP_NORMALS_AT_PIXELS_FIXED(1)
BP_NORMALS_AT_PIXELS_FIXED(2)
BP_NORMALS_AT_PIXELS_FIXED(3)
