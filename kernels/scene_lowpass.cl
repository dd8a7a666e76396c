/* Low-pass filtered range image: the mean depth of the valid pixels in a (2r+1)^2 box around
 * each valid pixel, as two separable passes (rows, then columns) so the cost is O(r) a pixel.
 * Pixels with no data stay no data (0): the filter smooths the surface, it does not fill holes,
 * so a hole can never become the "highest point". */
#pragma OPENCL FP_CONTRACT OFF
#include "scene_shared.h"

/* A pixel counts when it has data and, with a "may be used" mask (kernels/scene_mask.cl), when
 * the mask keeps it; mask 0 (a null pointer constant) means no mask. The masked kernels equal the
 * unmasked ones on the masked points (masked_points: the others all 0) without writing them. */
inline bool lowpass_counts(__global const float4* points, __global const uchar* mask,
                           const int i) {
  return points[i].w != 0.0f && (mask == 0 || mask[i] != 0);
}

/* Pass 1: per pixel, (sum of z, count) of the valid pixels in its row window. */
inline void lowpass_row(__global const float4* points, __global const uchar* mask,
                        const uint width, const uint height, const int radius,
                        __global float2* row_sums) {
  const uint i = get_global_id(0);
  if (i >= width * height) return;
  const int u = (int)(i % width), row = (int)(i - (uint)u);
  const int u0 = max(u - radius, 0), u1 = min(u + radius, (int)width - 1);
  float sum = 0.0f, count = 0.0f;
  for (int x = u0; x <= u1; ++x) {
    if (!lowpass_counts(points, mask, row + x)) continue;
    sum += points[row + x].z;
    count += 1.0f;
  }
  row_sums[i] = (float2)(sum, count);
}

/* Pass 2: per valid pixel, the column sum of the row sums divided by the column count. */
inline void lowpass_col(__global const float4* points, __global const uchar* mask,
                        __global const float2* row_sums, const uint width, const uint height,
                        const int radius, __global float* filtered) {
  const uint i = get_global_id(0);
  if (i >= width * height) return;
  if (!lowpass_counts(points, mask, (int)i)) {
    filtered[i] = 0.0f;
    return;
  }
  const int u = (int)(i % width), v = (int)(i / width);
  const int v0 = max(v - radius, 0), v1 = min(v + radius, (int)height - 1);
  float sum = 0.0f, count = 0.0f;
  for (int y = v0; y <= v1; ++y) {
    const float2 s = row_sums[y * (int)width + u];
    sum += s.x;
    count += s.y;
  }
  filtered[i] = sum / count; /* count >= 1: the centre itself is valid */
}

__kernel void lowpass_rows(__global const float4* points, const uint width, const uint height,
                           const int radius, __global float2* row_sums) {
  lowpass_row(points, 0, width, height, radius, row_sums);
}

__kernel void lowpass_cols(__global const float4* points, __global const float2* row_sums,
                           const uint width, const uint height, const int radius,
                           __global float* filtered) {
  lowpass_col(points, 0, row_sums, width, height, radius, filtered);
}

__kernel void lowpass_rows_masked(__global const float4* points, __global const uchar* mask,
                                  const uint width, const uint height, const int radius,
                                  __global float2* row_sums) {
  lowpass_row(points, mask, width, height, radius, row_sums);
}

__kernel void lowpass_cols_masked(__global const float4* points, __global const uchar* mask,
                                  __global const float2* row_sums, const uint width,
                                  const uint height, const int radius, __global float* filtered) {
  lowpass_col(points, mask, row_sums, width, height, radius, filtered);
}
