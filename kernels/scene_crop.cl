/* The points (and normals) of an organised image inside a sphere, compacted in pixel order by
 * a deterministic two-pass prefix sum: count per chunk, exclusive scan of the chunk counts
 * (host, a few hundred values), then each chunk writes its points from its offset on. The
 * crop's order is therefore the pixel order, whatever the device's scheduling. */
#pragma OPENCL FP_CONTRACT OFF
#include "scene_shared.h"

static inline bool crop_keeps(const float4 p, const float4 nrm, const float4 centre,
                              const float radius2, const uint require_normal) {
  if (p.w == 0.0f) return false;
  if (require_normal && nrm.w == 0.0f) return false;
  return bp_dist2(p.x, p.y, p.z, centre.x, centre.y, centre.z) <= radius2;
}

__kernel void crop_count(__global const float4* points, __global const float4* normals,
                         const uint n, const uint chunk, const float4 centre,
                         const float radius2, const uint require_normal,
                         __global uint* counts) {
  const uint g = get_global_id(0);
  const uint begin = g * chunk;
  if (begin >= n) return;
  const uint end = min(begin + chunk, n);
  uint count = 0;
  for (uint i = begin; i < end; ++i)
    count += crop_keeps(points[i], normals[i], centre, radius2, require_normal) ? 1u : 0u;
  counts[g] = count;
}

__kernel void crop_scatter(__global const float4* points, __global const float4* normals,
                           const uint n, const uint chunk, const float4 centre,
                           const float radius2, const uint require_normal,
                           __global const uint* offsets, __global float4* out_points,
                           __global float4* out_normals) {
  const uint g = get_global_id(0);
  const uint begin = g * chunk;
  if (begin >= n) return;
  const uint end = min(begin + chunk, n);
  uint o = offsets[g];
  for (uint i = begin; i < end; ++i)
    if (crop_keeps(points[i], normals[i], centre, radius2, require_normal)) {
      out_points[o] = points[i];
      out_normals[o] = normals[i];
      ++o;
    }
}

/* The pixels of a rectangle [rect.x, rect.z) x [rect.y, rect.w) (columns x rows) whose point lies
 * inside the sphere, with no normal needed: the detector crops first and computes normals only
 * for the points it keeps. The rectangle (host: crop_pixel_rect) contains the sphere's image,
 * so this is the full-image crop without the pixels that cannot pass. Work item g scans row
 * rect.y + g left to right: the same two-pass compaction in pixel order as above. */
static inline bool crop_rect_keeps(const float4 p, const float4 centre, const float radius2) {
  return p.w != 0.0f && bp_dist2(p.x, p.y, p.z, centre.x, centre.y, centre.z) <= radius2;
}

__kernel void crop_rect_count(__global const float4* points, const uint width, const uint4 rect,
                              const float4 centre, const float radius2, __global uint* counts) {
  const uint g = get_global_id(0);
  if (g >= rect.w - rect.y) return;
  const uint row = (rect.y + g) * width;
  uint count = 0;
  for (uint x = rect.x; x < rect.z; ++x)
    count += crop_rect_keeps(points[row + x], centre, radius2) ? 1u : 0u;
  counts[g] = count;
}

__kernel void crop_rect_scatter(__global const float4* points, const uint width, const uint4 rect,
                                const float4 centre, const float radius2,
                                __global const uint* offsets, __global uint* out_pixels,
                                __global float4* out_points) {
  const uint g = get_global_id(0);
  if (g >= rect.w - rect.y) return;
  const uint row = (rect.y + g) * width;
  uint o = offsets[g];
  for (uint x = rect.x; x < rect.z; ++x) {
    const float4 p = points[row + x];
    if (crop_rect_keeps(p, centre, radius2)) {
      out_pixels[o] = row + x;
      out_points[o] = p;
      ++o;
    }
  }
}

/* The same two passes with a "may be used" mask (kernels/scene_mask.cl, one uchar a pixel): a
 * pixel the mask does not keep never enters a neighbourhood. */
__kernel void crop_rect_count_masked(__global const float4* points, __global const uchar* mask,
                                     const uint width, const uint4 rect, const float4 centre,
                                     const float radius2, __global uint* counts) {
  const uint g = get_global_id(0);
  if (g >= rect.w - rect.y) return;
  const uint row = (rect.y + g) * width;
  uint count = 0;
  for (uint x = rect.x; x < rect.z; ++x)
    count += (mask[row + x] && crop_rect_keeps(points[row + x], centre, radius2)) ? 1u : 0u;
  counts[g] = count;
}

__kernel void crop_rect_scatter_masked(__global const float4* points, __global const uchar* mask,
                                       const uint width, const uint4 rect, const float4 centre,
                                       const float radius2, __global const uint* offsets,
                                       __global uint* out_pixels, __global float4* out_points) {
  const uint g = get_global_id(0);
  if (g >= rect.w - rect.y) return;
  const uint row = (rect.y + g) * width;
  uint o = offsets[g];
  for (uint x = rect.x; x < rect.z; ++x) {
    const float4 p = points[row + x];
    if (mask[row + x] && crop_rect_keeps(p, centre, radius2)) {
      out_pixels[o] = row + x;
      out_points[o] = p;
      ++o;
    }
  }
}
