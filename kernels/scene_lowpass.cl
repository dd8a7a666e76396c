/* Low-pass filtered range image: the mean depth of the valid pixels in a (2r+1)^2 box around
 * each valid pixel, as two separable passes (rows, then columns) so the cost is O(r) a pixel.
 * Pixels with no data stay no data (0): the filter smooths the surface, it does not fill holes,
 * so a hole can never become the "highest point". */
#pragma OPENCL FP_CONTRACT OFF
#include "scene_shared.h"

/* Pass 1: per pixel, (sum of z, count) of the valid pixels in its row window. */
__kernel void lowpass_rows(__global const float4* points, const uint width, const uint height,
                           const int radius, __global float2* row_sums) {
  const uint i = get_global_id(0);
  if (i >= width * height) return;
  const int u = (int)(i % width), row = (int)(i - (uint)u);
  const int u0 = max(u - radius, 0), u1 = min(u + radius, (int)width - 1);
  float sum = 0.0f, count = 0.0f;
  for (int x = u0; x <= u1; ++x) {
    const float4 p = points[row + x];
    if (p.w == 0.0f) continue;
    sum += p.z;
    count += 1.0f;
  }
  row_sums[i] = (float2)(sum, count);
}

/* Pass 2: per valid pixel, the column sum of the row sums divided by the column count. */
__kernel void lowpass_cols(__global const float4* points, __global const float2* row_sums,
                           const uint width, const uint height, const int radius,
                           __global float* filtered) {
  const uint i = get_global_id(0);
  if (i >= width * height) return;
  if (points[i].w == 0.0f) {
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
