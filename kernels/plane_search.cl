/* The in-plane search of thin parts (host/detect/refine/plane_search.hpp): the edge step of many poses.
 *
 * point_depths: one work item per pixel: the z of a point image (float4, w = 1 where there is
 * data), 0 where there is none. The search reads only the depth, at random pixels over the
 * part's footprint: a float a pixel is a quarter of the memory a float4 image is, and the
 * footprint of a part at 2 m in a 2064 x 1544 image then fits in a core's cache.
 *
 * edge_step_scores: one work item per pose (12 floats: R row-major, then t; model to camera).
 * For every `stride`-th edge probe (model frame, with the normal of the face it continues) that
 * faces the camera at the pose, the depth the sensor sees beyond the pose's edge, along the
 * probe's ray: the excess of the measured depth over the probe's, clamped to [.., tolerance];
 * no depth counts as a full tolerance (a shadow or a drop), something more than a tolerance in
 * front says nothing (the probe is skipped). The score is the mean over the probes counted, or
 * -1 with fewer than BP_EDGE_SEARCH_MIN_PROBES. A right pose of a sheet lying on a sheet scores
 * about its thickness; a pose shifted or turned in the sheet's plane has probes on the sheet
 * itself and scores less. Points with w = 1 are the part's own surface instead: their excess,
 * clamped to [0, tolerance] (the pose hanging over what the sensor sees), is averaged apart and
 * taken off, so that a pose lying off the sheet, over what lies beneath, does not score as if
 * its edges stepped down (also at least BP_EDGE_SEARCH_MIN_PROBES of them, or -1). No depth under
 * the part's own surface counts half a tolerance, as missing depth counts half in verification:
 * it may be the void beside a pile (the pose hangs over nothing) or the sensor's loss on real
 * surface, which on shiny sheet metal comes in patches: as a full tolerance it drew the search
 * off a plate's patches with depth (docs/decisions/2026-11-25-plane-search-no-depth-half.md).
 * Written out identically in edge_step_scores_reference. */
#pragma OPENCL FP_CONTRACT OFF
#include "binpick_shared.h"

#define BP_EDGE_SEARCH_MIN_PROBES 10u

__kernel void point_depths(__global const float4* points, const uint n, __global float* depth) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float4 p = points[i];
  depth[i] = p.w != 0.0f ? p.z : 0.0f;
}

/* Eight probes at a time, one a lane (probe index t, in units of the stride, in lane t % 8), so
 * the CPU device runs the arithmetic as 8-wide vectors; each lane sums its own probes and the
 * lanes are added pairwise at the end, in the order edge_step_scores_reference adds them. */
#define BP_GATHER(l)                                                            \
  {                                                                             \
    const uint i = j + (l) * stride;                                            \
    const float4 a = probes[i < n_probes ? i : last];                           \
    const float4 b = normals[i < n_probes ? i : last];                          \
    qx.s##l = a.x, qy.s##l = a.y, qz.s##l = a.z, qw.s##l = a.w;                 \
    mx.s##l = b.x, my.s##l = b.y, mz.s##l = b.z;                                \
    there.s##l = i < n_probes ? -1 : 0;                                         \
  }
#define BP_DEPTH(l) \
  sz.s##l = seen.s##l ? depth[(size_t)fv.s##l * cam.width + (size_t)fu.s##l] : 0.0f;

__kernel void edge_step_scores(__global const float* depth, const bp_camera cam,
                               __global const float4* probes, __global const float4* normals,
                               const uint n_probes, const uint stride,
                               __global const float* poses, const uint n_poses,
                               const float tolerance, __global float* scores) {
  const uint k = get_global_id(0);
  if (k >= n_poses) return;
  __global const float* P = poses + 12 * (size_t)k;
  float8 sum = 0.0f, own = 0.0f;
  int8 count = 0, own_count = 0;
  const uint last = n_probes > 0u ? n_probes - 1u : 0u;
  for (uint j = 0; j < n_probes; j += 8u * stride) {
    float8 qx, qy, qz, qw, mx, my, mz;
    int8 there;
    BP_GATHER(0) BP_GATHER(1) BP_GATHER(2) BP_GATHER(3)
    BP_GATHER(4) BP_GATHER(5) BP_GATHER(6) BP_GATHER(7)
    const float8 x = P[0] * qx + P[1] * qy + P[2] * qz + P[9];
    const float8 y = P[3] * qx + P[4] * qy + P[5] * qz + P[10];
    const float8 z = P[6] * qx + P[7] * qy + P[8] * qz + P[11];
    const float8 nx = P[0] * mx + P[1] * my + P[2] * mz;
    const float8 ny = P[3] * mx + P[4] * my + P[5] * mz;
    const float8 nz = P[6] * mx + P[7] * my + P[8] * mz;
    const int8 facing = there & (z > 0.0f) & (nx * x + ny * y + nz * z < 0.0f);
    const float8 fu = floor(cam.fx * x / z + cam.cx + 0.5f);
    const float8 fv = floor(cam.fy * y / z + cam.cy + 0.5f);
    const int8 seen = facing & (fu >= 0.0f) & (fv >= 0.0f) & (fu < (float)cam.width) &
                      (fv < (float)cam.height);
    float8 sz;
    BP_DEPTH(0) BP_DEPTH(1) BP_DEPTH(2) BP_DEPTH(3)
    BP_DEPTH(4) BP_DEPTH(5) BP_DEPTH(6) BP_DEPTH(7)
    const int8 is_own = qw != 0.0f;
    const int8 has = sz != 0.0f;
    /* no depth: see the top */
    const float8 missing = select((float8)tolerance, (float8)(0.5f * tolerance), is_own);
    const float8 excess = (sz - z) * (sqrt(x * x + y * y + z * z) / z);
    const int8 used = seen & ~(has & (excess < -tolerance));
    const float8 e = select(missing, fmin(excess, tolerance), has);
    own += select((float8)0.0f, fmax(e, 0.0f), used & is_own);
    own_count -= used & is_own;
    sum += select((float8)0.0f, e, used & ~is_own);
    count -= used & ~is_own;
  }
  const float s = ((sum.s0 + sum.s1) + (sum.s2 + sum.s3)) + ((sum.s4 + sum.s5) + (sum.s6 + sum.s7));
  const float o = ((own.s0 + own.s1) + (own.s2 + own.s3)) + ((own.s4 + own.s5) + (own.s6 + own.s7));
  const uint c = (uint)(count.s0 + count.s1 + count.s2 + count.s3 + count.s4 + count.s5 +
                        count.s6 + count.s7);
  const uint oc = (uint)(own_count.s0 + own_count.s1 + own_count.s2 + own_count.s3 +
                         own_count.s4 + own_count.s5 + own_count.s6 + own_count.s7);
  scores[k] = c >= BP_EDGE_SEARCH_MIN_PROBES && oc >= BP_EDGE_SEARCH_MIN_PROBES
                  ? s / (float)c - o / (float)oc
                  : -1.0f;
}
