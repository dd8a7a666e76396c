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

/* The hypothesis of pixel best_i (BP_NO_PIXEL: none, all zero), with the 3D point on the
 * pixel's ray at the filtered depth. */
inline bp_hypothesis hyp_at(const uint best_i, __global const float4* points,
                            __global const float* filtered, const uint width) {
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
  return h;
}

/* Round, stage 2 (one work item): the best of the chunks or tiles, the smaller pixel index
 * among equal depths (for chunks, which are in pixel order, the first chunk; tiles are not in
 * pixel order, so the rule is explicit); writes hyps[k], with the 3D point on the pixel's ray
 * at the filtered depth. */
__kernel void hyp_select(__global const float* part_depth, __global const uint* part_pixel,
                         const uint parts, __global const float4* points,
                         __global const float* filtered, const uint width, const uint k,
                         __global bp_hypothesis* hyps) {
  if (get_global_id(0) != 0) return;
  float best = INFINITY;
  uint best_i = BP_NO_PIXEL;
  for (uint g = 0; g < parts; ++g) {
    const uint i = part_pixel[g];
    if (i == BP_NO_PIXEL) continue;
    if (part_depth[g] < best || (part_depth[g] == best && i < best_i)) {
      best = part_depth[g];
      best_i = i;
    }
  }
  hyps[k] = hyp_at(best_i, points, filtered, width);
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

/* Before the first round, when "highest" is along the bin's up (u, a unit vector from its
 * floor towards the camera's side) rather than nearest the camera: each pixel's key is -u . p,
 * p its point at the filtered depth (on the ray, as hyp_at places it), and the argmin kernels
 * read the keys in place of the filtered depth (hyp_select still places the point from the
 * filtered depth). 0 stays no data; a key at or below 0 (a point level with the camera or
 * above it along u) becomes the least positive float, so it is still a valid pixel. */
__kernel void hyp_height_key(__global const float4* points, __global const float* filtered,
                             const uint n, const float ux, const float uy, const float uz,
                             __global float* key) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float d = filtered[i];
  if (!(d > 0.0f)) {
    key[i] = 0.0f;
    return;
  }
  const float4 p = points[i];
  const float s = d / p.z;
  const float x = p.x * s, y = p.y * s;
  const float k = -((ux * x + uy * y) + uz * d);
  key[i] = k > 0.0f ? k : FLT_MIN;
}

/* Before the first round, with a "may be used" mask (kernels/scene_mask.cl): the pixels it
 * does not keep start excluded, so they never become a highest point. */
__kernel void hyp_exclude_masked(__global const uchar* mask, const uint n,
                                 __global uchar* excluded) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  excluded[i] = mask[i] ? (uchar)0 : (uchar)1;
}

/* Rounds on a depth image's points (host/detect/hypotheses/hypotheses.cpp, HypothesisOptions::camera): the
 * same choices as the chunk kernels above, with less work after the first round. The image is
 * cut into tiles of tile_w x tile_h pixels; a round excludes only inside the rectangle of the
 * image the exclusion sphere projects into (no pixel outside it has its point within the
 * radius), so only the tiles that rectangle touches need their argmin again. */

/* Stage 1 on tiles: work item g scans tile (tx0 + g % ntx, ty0 + g / ntx) row by row, i.e. in
 * pixel order, so a strict "<" keeps the smallest index among equal depths; writes its result
 * at the tile's index ty * tiles_x + tx. */
__kernel void hyp_tile_argmin(__global const float* filtered, __global const uchar* excluded,
                              const uint width, const uint height, const uint tile_w,
                              const uint tile_h, const uint tiles_x, const uint tx0,
                              const uint ty0, const uint ntx, const uint nty,
                              __global float* part_depth, __global uint* part_pixel) {
  const uint g = get_global_id(0);
  if (g >= ntx * nty) return;
  const uint tx = tx0 + g % ntx, ty = ty0 + g / ntx;
  const uint u0 = tx * tile_w, v0 = ty * tile_h;
  const uint u1 = min(u0 + tile_w, width), v1 = min(v0 + tile_h, height);
  float best = INFINITY;
  uint best_i = BP_NO_PIXEL;
  for (uint v = v0; v < v1; ++v)
    for (uint i = v * width + u0; i < v * width + u1; ++i) {
      const float d = filtered[i];
      if (d > 0.0f && !excluded[i] && d < best) {
        best = d;
        best_i = i;
      }
    }
  part_depth[ty * tiles_x + tx] = best;
  part_pixel[ty * tiles_x + tx] = best_i;
}

/* Stage 3 on a rectangle: hyp_exclude for the pixels of columns [u0, u0 + rect_w) and rows
 * [v0, v0 + rect_h) only (work item g: column u0 + g % rect_w, row v0 + g / rect_w). */
__kernel void hyp_exclude_rect(__global const float4* points, const uint width, const uint u0,
                               const uint v0, const uint rect_w, const uint rect_h,
                               __global const bp_hypothesis* hyps, const uint k,
                               const float radius2, __global uchar* excluded) {
  const uint g = get_global_id(0);
  if (g >= rect_w * rect_h) return;
  const bp_hypothesis h = hyps[k];
  if (h.pixel == BP_NO_PIXEL) return;
  const uint i = (v0 + g / rect_w) * width + u0 + g % rect_w;
  const float4 p = points[i];
  if (i == h.pixel || (p.w != 0.0f && bp_dist2(p.x, p.y, p.z, h.x, h.y, h.z) <= radius2))
    excluded[i] = 1;
}
