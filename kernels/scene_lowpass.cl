/* Low-pass filtered range image: the mean depth of the valid pixels in a (2r+1)^2 box around
 * each valid pixel, as two separable passes (rows, then columns) so the cost is O(r) a pixel.
 * Pixels with no data stay no data (0): the filter smooths the surface, it does not fill holes,
 * so a hole can never become the "highest point".
 *
 * Pass 0 writes each pixel as a pair (z, 1) where it counts and (0, 0) where it does not, so the
 * passes after it add pairs without a branch and read 8 bytes a tap instead of a 16-byte point
 * and a mask byte. Adding (0, 0) leaves a sum of depths and counts as it is (x + 0 = x for every
 * x >= 0), so every sum is the sum of the valid pixels alone, added in the same order. */
#pragma OPENCL FP_CONTRACT OFF
#include "scene_shared.h"

/* A pixel counts when it has data and, with a "may be used" mask (kernels/scene_mask.cl), when
 * the mask keeps it; mask 0 (a null pointer constant) means no mask. The masked kernels equal the
 * unmasked ones on the masked points (masked_points: the others all 0) without writing them. */
inline void lowpass_pair(__global const float4* points, __global const uchar* mask, const uint n,
                         __global float2* pairs) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float4 p = points[i];
  const bool counts = p.w != 0.0f && (mask == 0 || mask[i] != 0);
  pairs[i] = counts ? (float2)(p.z, 1.0f) : (float2)(0.0f, 0.0f);
}

__kernel void lowpass_pairs(__global const float4* points, const uint n, __global float2* pairs) {
  lowpass_pair(points, 0, n, pairs);
}

__kernel void lowpass_pairs_masked(__global const float4* points, __global const uchar* mask,
                                   const uint n, __global float2* pairs) {
  lowpass_pair(points, mask, n, pairs);
}

/* The row and column passes take a block of LP_BLOCK pixels of one row a work item (the host's
 * lowpass_work_items). Where the block's windows all lie inside the image, one vector add a tap
 * adds that tap to all LP_BLOCK sums: LP_BLOCK independent sums instead of one chain of 2r + 1
 * dependent adds a pixel (PoCL does not vectorise the per-pixel loop, whose bounds differ between
 * work items), and each pixel's sum is the same sum of the same terms in the same order as the
 * per-pixel loop that the blocks at the image's sides run. */
#define LP_BLOCK 8

/* Pass 1: per pixel, (sum of z, count) of the valid pixels in its row window. */
__kernel void lowpass_rows(__global const float2* pairs, const uint width, const uint height,
                           const int radius, __global float2* row_sums) {
  const uint blocks_per_row = (width + LP_BLOCK - 1) / LP_BLOCK;
  const uint b = get_global_id(0);
  if (b >= blocks_per_row * height) return;
  const uint v = b / blocks_per_row;
  const int first = (int)((b - v * blocks_per_row) * LP_BLOCK), row = (int)(v * width);
  if (first >= radius && first + LP_BLOCK - 1 + radius < (int)width) {
    __global const float* from = (__global const float*)(pairs + row + first);
    float16 sum = (float16)(0.0f);
    for (int k = -radius; k <= radius; ++k) sum += vload16(0, from + 2 * k);
    vstore16(sum, 0, (__global float*)(row_sums + row + first));
    return;
  }
  const int last = min(first + LP_BLOCK, (int)width);
  for (int u = first; u < last; ++u) {
    const int u0 = max(u - radius, 0), u1 = min(u + radius, (int)width - 1);
    float2 sum = (float2)(0.0f, 0.0f);
    for (int x = u0; x <= u1; ++x) sum += pairs[row + x];
    row_sums[row + u] = sum;
  }
}

/* Pass 2: per valid pixel, the column sum of the row sums divided by the column count. */
__kernel void lowpass_cols(__global const float2* pairs, __global const float2* row_sums,
                           const uint width, const uint height, const int radius,
                           __global float* filtered) {
  const uint blocks_per_row = (width + LP_BLOCK - 1) / LP_BLOCK;
  const uint b = get_global_id(0);
  if (b >= blocks_per_row * height) return;
  const int v = (int)(b / blocks_per_row);
  const int first = (int)((b - (uint)v * blocks_per_row) * LP_BLOCK), row = v * (int)width;
  if (v >= radius && v + radius < (int)height && first + LP_BLOCK <= (int)width) {
    float16 sum = (float16)(0.0f);
    for (int k = -radius; k <= radius; ++k)
      sum += vload16(0, (__global const float*)(row_sums + row + k * (int)width + first));
    const float8 counts = vload16(0, (__global const float*)(pairs + row + first)).odd;
    /* An invalid pixel's 0 / 0 is replaced by its 0. */
    const float8 mean = sum.even / sum.odd;
    vstore8(select(mean, (float8)(0.0f), counts == (float8)(0.0f)), 0, filtered + row + first);
    return;
  }
  const int last = min(first + LP_BLOCK, (int)width);
  for (int u = first; u < last; ++u) {
    const int i = row + u;
    if (pairs[i].y == 0.0f) {
      filtered[i] = 0.0f;
      continue;
    }
    const int v0 = max(v - radius, 0), v1 = min(v + radius, (int)height - 1);
    float2 sum = (float2)(0.0f, 0.0f);
    for (int y = v0; y <= v1; ++y) sum += row_sums[y * (int)width + u];
    filtered[i] = sum.x / sum.y; /* count >= 1: the centre itself is valid */
  }
}

/* The points moved along their rays to the low-passed depth where it has a value (elsewhere
 * the point as it is): the depth image with the sensor's noise averaged over the box, which the
 * in-plane search of thin parts reads on noisy images (host/detect/scene/scene_lowpass.hpp). */
__kernel void lowpass_points(__global const float4* points, __global const float* filtered,
                             const uint n, __global float4* out) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float4 p = points[i];
  const float f = filtered[i];
  if (!(p.w != 0.0f && f > 0.0f)) {
    out[i] = p;
    return;
  }
  const float s = f / p.z;
  out[i] = (float4)(p.x * s, p.y * s, p.z * s, 1.0f);
}
