/* The per-pixel "may be used" mask of a scene (--roi, --bin; host/detect/bin/scene_mask.cpp): one
 * uchar a pixel, 1 where the pixel has data and its point lies inside every active box of the
 * region. Masked pixels never become highest points, never enter a crop and never vote. */
#pragma OPENCL FP_CONTRACT OFF
#include "scene_mask_shared.h"

__kernel void scene_mask(__global const float4* points, const uint n, const bp_region region,
                         __global uchar* mask) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float4 p = points[i];
  mask[i] = bp_region_keeps(&region, p.x, p.y, p.z, p.w);
}

/* The points that may be used, the others without data (all 0): the low-pass range image of
 * the highest points is computed on these, so that a masked rim or wall does not pull the
 * filtered depth of the pixels next to it toward the camera. */
__kernel void masked_points(__global const float4* points, __global const uchar* mask,
                            const uint n, __global float4* out) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  out[i] = mask[i] ? points[i] : (float4)(0.0f, 0.0f, 0.0f, 0.0f);
}

/* Each pixel's class against the rim (bp_over_rim_class) and its height in the bin's frame;
 * *beyond (0 before) counts the pixels beyond a side, so that the host reads the classes back
 * only when something stands over the rim outside the bin (rarely: an arm, a hose). */
__kernel void over_rim_classes(__global const float4* points, const uint n, const bp_over_rim g,
                               __global uchar* classes, __global float* heights,
                               __global uint* beyond) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float4 p = points[i];
  float h;
  const int c = bp_over_rim_class(&g, p.x, p.y, p.z, p.w, &h);
  classes[i] = (uchar)c;
  heights[i] = h;
  if (c == BP_OVER_RIM_OUT) atomic_inc(beyond);
}
