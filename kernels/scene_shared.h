/* Types and small functions of scene preparation (normals, low-pass, highest points, crops)
 * shared by the OpenCL C kernels (kernels/scene_*.cl) and their C++ references, so that both
 * sides compute the same predicate with the same float operations in the same order.
 * Valid OpenCL C 1.2 and valid C++20; structs hold only 4-byte scalars. */
#ifndef BINPICK_SCENE_SHARED_H
#define BINPICK_SCENE_SHARED_H

#include "binpick_shared.h"

#ifdef __OPENCL_VERSION__
#define BP_SQRT sqrt
#define BP_FABS fabs
#define BP_CEIL ceil
#else
#define BP_SQRT std::sqrt
#define BP_FABS std::fabs
#define BP_CEIL std::ceil
#endif

/* "No pixel": no valid, not yet excluded pixel was left for a hypothesis. */
#define BP_NO_PIXEL 0xFFFFFFFFu

/* A plane fit is degenerate (the window's points lie on a line or a point) when the middle
 * eigenvalue of the covariance is below this fraction of the largest. */
#define BP_NORMAL_DEGENERATE_RATIO 1e-4f

/* Normals over a metric neighbourhood: the window of a point at depth z covers `radius` mm,
 * r = ceil(radius * focal / z) pixels (at most BP_NORMAL_MAX_METRIC_RADIUS), sampled every
 * `step` pixels so that at most 2 BP_NORMAL_METRIC_HALF_SAMPLES + 1 rows and columns are read:
 * the cost stays bounded however near or large the part. */
#define BP_NORMAL_MAX_METRIC_RADIUS 96
#define BP_NORMAL_METRIC_HALF_SAMPLES 6
BP_FN void bp_metric_window(float z, float radius, float focal, int* r, int* step) {
  float px = BP_CEIL(radius * focal / z);
  if (!(px >= 1.0f)) px = 1.0f;
  if (px > (float)BP_NORMAL_MAX_METRIC_RADIUS) px = (float)BP_NORMAL_MAX_METRIC_RADIUS;
  *r = (int)px;
  *step = (*r + BP_NORMAL_METRIC_HALF_SAMPLES - 1) / BP_NORMAL_METRIC_HALF_SAMPLES;
}

/* Cyclic Jacobi sweeps of the 3x3 eigen solver: convergence is quadratic, so 8 sweeps reach
 * float precision for any input; a fixed bound keeps the kernel's run time bounded. */
#define BP_JACOBI_SWEEPS 8

/* One highest point: the pixel (or cloud point index), its low-pass filtered depth and the
 * 3D point on the pixel's ray at that depth (mm, camera frame). */
typedef struct {
  bp_u32 pixel; /* BP_NO_PIXEL if none was left */
  bp_u32 u, v;
  float depth;
  float x, y, z;
  bp_u32 reserved[2];
} bp_hypothesis;

/* Squared distance, written out so the kernel (compiled with FP_CONTRACT OFF) and the host
 * round identically: crop and exclusion tests must agree exactly. */
BP_FN float bp_dist2(float ax, float ay, float az, float bx, float by, float bz) {
  const float dx = ax - bx, dy = ay - by, dz = az - bz;
  return dx * dx + dy * dy + dz * dz;
}

/* Eigen-decomposition of the symmetric 3x3 matrix a (row-major, overwritten) by cyclic Jacobi
 * rotations (Numerical Recipes' formulation): robust for repeated eigenvalues and
 * deterministic. On return the diagonal of a holds the eigenvalues, the columns of v
 * (row-major) the unit eigenvectors. */
BP_FN void bp_sym3_jacobi(float* a, float* v) {
  for (int i = 0; i < 9; ++i) v[i] = (i % 4 == 0) ? 1.0f : 0.0f;
  for (int sweep = 0; sweep < BP_JACOBI_SWEEPS; ++sweep) {
    const float off = BP_FABS(a[1]) + BP_FABS(a[2]) + BP_FABS(a[5]);
    if (off == 0.0f) break;
    for (int pq = 0; pq < 3; ++pq) {
      const int p = pq == 2 ? 1 : 0;
      const int q = pq == 0 ? 1 : 2;
      const float apq = a[3 * p + q];
      const float app = a[4 * p], aqq = a[4 * q];
      /* Below float resolution of the diagonal the rotation changes nothing: drop it. */
      if (BP_FABS(apq) <= 1e-9f * (BP_FABS(app) + BP_FABS(aqq))) {
        a[3 * p + q] = 0.0f;
        a[3 * q + p] = 0.0f;
        continue;
      }
      const float theta = (aqq - app) / (2.0f * apq);
      /* The smaller root of t^2 + 2 t theta - 1 = 0; 1 / (2 theta) when theta^2 would
       * overflow. */
      float t = BP_FABS(theta) > 1e18f
                    ? 0.5f / theta
                    : 1.0f / (BP_FABS(theta) + BP_SQRT(theta * theta + 1.0f));
      if (theta < 0.0f && BP_FABS(theta) <= 1e18f) t = -t;
      const float c = 1.0f / BP_SQRT(t * t + 1.0f);
      const float s = t * c;
      const int r = 3 - p - q; /* the third index */
      const float arp = a[3 * r + p], arq = a[3 * r + q];
      a[3 * r + p] = a[3 * p + r] = c * arp - s * arq;
      a[3 * r + q] = a[3 * q + r] = s * arp + c * arq;
      a[4 * p] = app - t * apq;
      a[4 * q] = aqq + t * apq;
      a[3 * p + q] = a[3 * q + p] = 0.0f;
      for (int k = 0; k < 3; ++k) {
        const float vkp = v[3 * k + p], vkq = v[3 * k + q];
        v[3 * k + p] = c * vkp - s * vkq;
        v[3 * k + q] = s * vkp + c * vkq;
      }
    }
  }
}

#endif /* BINPICK_SCENE_SHARED_H */
