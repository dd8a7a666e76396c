/* All point pair features of a cloud, one row of n pairs per reference point m_r: the key
 * (BP_PPF_NO_KEY for a skipped pair, including m_r with itself) and alpha_m. Used to check the
 * device's features against the C++ reference; the table build (ppf_table.cl) computes the same
 * features on the fly instead of storing n^2 of them. */
#pragma OPENCL FP_CONTRACT OFF
#include "binpick_shared.h"

__kernel void ppf_pair_features(__global const float4* points, __global const float4* normals,
                                const uint n, const bp_ppf_quant q, __global uint* keys,
                                __global float* alphas) {
  const uint r = get_global_id(0);
  if (r >= n) return;
  const float3 pr = points[r].xyz;
  const float3 nr = normals[r].xyz;
  for (uint i = 0; i < n; i += 8u) {
    float8 alpha;
    const uint8 key = bp_ppf_pairs_at(pr, nr, points, normals, i, n, r, q, &alpha);
    bp_store8(key, keys + (size_t)r * n + i, n - i);
    bp_store8(as_uint8(alpha), (__global uint*)alphas + (size_t)r * n + i, n - i);
  }
}
