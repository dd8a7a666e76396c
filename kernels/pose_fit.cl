/* One step of pose refinement and the verification counts, for many poses at once
 * (kernels/pose_fit_shared.h says what is counted and why).
 *
 * pose_fit: one work group of BP_FIT_GROUP items per pose. The group clears the pose's z-buffer
 * grid, writes every posed model point's depth into it (atomic_min on the float's bits, which
 * order like the floats for positive values), then classifies every point against the grid
 * and the measured point image and adds up the Gauss-Newton terms, and (outline > 0) classifies
 * the empty cells next to filled ones against the measured depth. Each work item writes its
 * own partial sums (sums[pose * BP_FIT_GROUP + item]); the host adds the 64 in double, so the
 * result does not depend on a float reduction order. The grid of a pose is touched only by its
 * own group, so the group's barriers are enough. With f.residuals, each model point's residual
 * goes to residuals[pose * n_model + point] (NaN where the point gives no term) and its class to
 * classes[pose * n_model + point]; residuals and classes may
 * be a one-element buffer when no fit asks for them. */
#pragma OPENCL FP_CONTRACT OFF
#include "binpick_shared.h"
#include "pose_fit_shared.h"

__kernel void pose_fit(__global const float4* points, const bp_camera cam,
                       __global const float4* model_points, __global const float4* model_normals,
                       const uint n_model, __global const bp_pose_fit* fits, const uint n_fits,
                       __global uint* grids, __global bp_fit_sums* sums,
                       __global float* residuals, __global uchar* classes) {
  const uint k = get_group_id(0);
  const uint lid = get_local_id(0);
  if (k >= n_fits) return; /* the whole group: the launch is n_fits groups exactly */
  const bp_pose_fit f = fits[k];
  const bp_camera c = cam;
  __global uint* grid = grids + (size_t)k * BP_FIT_MAX_DIM * BP_FIT_MAX_DIM;
  const uint cells = f.dim * f.dim;
  for (uint i = lid; i < cells; i += BP_FIT_GROUP) grid[i] = 0x7f800000u; /* +inf */
  barrier(CLK_GLOBAL_MEM_FENCE);

  float q[3], nq[3];
  uint pixel = 0u, cell = 0u;
  for (uint j = lid; j < n_model; j += BP_FIT_GROUP) {
    const float4 m = model_points[j], n = model_normals[j];
    const int seen = bp_fit_project(&f, &c, m.x, m.y, m.z, n.x, n.y, n.z, q, nq, &pixel, &cell);
    /* Read first: most points lie behind their cell's nearest so far, and atomic_min is a
     * locked compare-and-swap loop on the CPU (a tenth of the kernel's time). The minimum is
     * the same: a value not below the cell's leaves it as atomic_min would. */
    if (seen && as_uint(q[2]) < grid[cell]) atomic_min(&grid[cell], as_uint(q[2]));
    /* The classification below reads this point's measured point: a pose's pixels are scattered
     * over an image of tens of MB, and fetched now they are in the cache by then. */
    if (seen == 2) BP_PREFETCH(points + pixel);
  }
  barrier(CLK_GLOBAL_MEM_FENCE);

  bp_fit_sums s;
  for (int i = 0; i < 21; ++i) s.jtj[i] = 0.0f;
  for (int i = 0; i < 6; ++i) s.jtr[i] = 0.0f;
  for (uint i = 0; i < BP_FIT_CLASSES; ++i) s.count[i] = 0u;
  s.cost = 0.0f;
  s.used = 0u;
  s.agreement = 0.0f;
  s.outline_continue = 0u;
  s.outline_step = 0u;
  float a[6];
  float r = 0.0f;
  __global float* own = residuals + (size_t)k * n_model;
  __global uchar* own_class = classes + (size_t)k * n_model;
  for (uint j = lid; j < n_model; j += BP_FIT_GROUP) {
    if (f.residuals != 0u) {
      own[j] = NAN;
      own_class[j] = (uchar)BP_FIT_HIDDEN;
    }
    const float4 m = model_points[j], n = model_normals[j];
    if (bp_fit_project(&f, &c, m.x, m.y, m.z, n.x, n.y, n.z, q, nq, &pixel, &cell) != 2) continue;
    const float4 p = points[pixel];
    float agree = 0.0f;
    const uint cls = bp_fit_classify(&f, &c, q, nq, as_float(grid[cell]), p.x, p.y, p.z, p.w, &agree);
    if (f.residuals != 0u) own_class[j] = (uchar)cls;
    ++s.count[cls];
    s.agreement += agree;
    if (cls == BP_FIT_HIDDEN || cls == BP_FIT_MISSING) continue;
    const float w = bp_fit_term(&f, q, nq, p.x, p.y, p.z, a, &r);
    if (w == 0.0f) continue;
    if (f.residuals != 0u) own[j] = r;
    ++s.used;
    int e = 0;
    for (int row = 0; row < 6; ++row) {
      for (int col = row; col < 6; ++col) s.jtj[e++] += w * a[row] * a[col];
      s.jtr[row] += w * a[row] * r;
    }
    s.cost += w * r * r;
  }
  if (f.outline > 0.0f) {
    const uint empty = 0x7f800000u, dim = f.dim;
    for (uint i = lid; i < cells; i += BP_FIT_GROUP) {
      if (grid[i] != empty) continue;
      const uint gu = i % dim, gv = i / dim;
      /* The nearest filled 4-neighbour (positive floats order like their bits). */
      uint zn = empty;
      if (gu + 1u < dim) zn = min(zn, grid[i + 1u]);
      if (gu > 0u) zn = min(zn, grid[i - 1u]);
      if (gv + 1u < dim) zn = min(zn, grid[i + dim]);
      if (gv > 0u) zn = min(zn, grid[i - dim]);
      if (zn == empty || !bp_fit_outline_pixel(&f, &c, gu, gv, &pixel)) continue;
      const float4 p = points[pixel];
      const uint cls = bp_fit_outline_class(&f, as_float(zn), p.z, p.w);
      if (cls == BP_FIT_OUTLINE_CONTINUE) ++s.outline_continue;
      else if (cls == BP_FIT_OUTLINE_STEP) ++s.outline_step;
    }
  }
  sums[(size_t)k * BP_FIT_GROUP + lid] = s;
}
