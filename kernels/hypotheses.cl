/* The highest points of a low-pass filtered range image (paper section III-C): repeatedly the
 * valid, not yet excluded pixel of smallest filtered depth (nearest the camera; ties go to the
 * smaller pixel index), then every pixel whose 3D point lies within the exclusion radius of it
 * is excluded. The three kernels of one round run without a read-back: the choice stays in
 * hyps[k] on the device and the exclusion kernel reads it from there. */
#pragma OPENCL FP_CONTRACT OFF
#include "scene_shared.h"

/* Round, stage 1: work item g scans pixels [g * chunk, (g + 1) * chunk) in order, so a strict
 * "<" keeps the smallest index among equal depths. filtered = 0 means no data. */
__kernel void hyp_chunk_argmin(__global const float* filtered, __global const uchar* excluded,
                               const uint n, const uint chunk, __global float* part_depth,
                               __global uint* part_pixel) {
  const uint g = get_global_id(0);
  const uint begin = g * chunk;
  if (begin >= n) return;
  const uint end = min(begin + chunk, n);
  float best = INFINITY;
  uint best_i = BP_NO_PIXEL;
  for (uint i = begin; i < end; ++i) {
    const float d = filtered[i];
    if (d > 0.0f && !excluded[i] && d < best) {
      best = d;
      best_i = i;
    }
  }
  part_depth[g] = best;
  part_pixel[g] = best_i;
}

/* Round, stage 2 (one work item): the best of the chunks, in chunk order for the same
 * tie-break; writes hyps[k], with the 3D point on the pixel's ray at the filtered depth. */
__kernel void hyp_select(__global const float* part_depth, __global const uint* part_pixel,
                         const uint parts, __global const float4* points,
                         __global const float* filtered, const uint width, const uint k,
                         __global bp_hypothesis* hyps) {
  if (get_global_id(0) != 0) return;
  float best = INFINITY;
  uint best_i = BP_NO_PIXEL;
  for (uint g = 0; g < parts; ++g)
    if (part_pixel[g] != BP_NO_PIXEL && part_depth[g] < best) {
      best = part_depth[g];
      best_i = part_pixel[g];
    }
  bp_hypothesis h;
  h.pixel = best_i;
  h.u = h.v = 0;
  h.depth = h.x = h.y = h.z = 0.0f;
  h.reserved[0] = h.reserved[1] = 0;
  if (best_i != BP_NO_PIXEL) {
    const float4 p = points[best_i];
    const float s = filtered[best_i] / p.z; /* p.z > 0: filtered is 0 where p has no data */
    h.u = best_i % width;
    h.v = best_i / width;
    h.depth = filtered[best_i];
    h.x = p.x * s;
    h.y = p.y * s;
    h.z = h.depth;
  }
  hyps[k] = h;
}

/* Round, stage 3: exclude the neighbourhood of hyps[k] (and its own pixel, which the radius
 * might miss when the filtered depth lies far from a noisy measured one). */
__kernel void hyp_exclude(__global const float4* points, const uint n,
                          __global const bp_hypothesis* hyps, const uint k, const float radius2,
                          __global uchar* excluded) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const bp_hypothesis h = hyps[k];
  if (h.pixel == BP_NO_PIXEL) return;
  const float4 p = points[i];
  if (i == h.pixel || (p.w != 0.0f && bp_dist2(p.x, p.y, p.z, h.x, h.y, h.z) <= radius2))
    excluded[i] = 1;
}

/* Before the first round, with a "may be used" mask (kernels/scene_mask.cl): the pixels it
 * does not keep start excluded, so they never become a highest point. */
__kernel void hyp_exclude_masked(__global const uchar* mask, const uint n,
                                 __global uchar* excluded) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  excluded[i] = mask[i] ? (uchar)0 : (uchar)1;
}
