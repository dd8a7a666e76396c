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
  for (uint i = 0; i < n; ++i) {
    float alpha = 0.0f;
    const uint key = i == r ? BP_PPF_NO_KEY
                            : bp_ppf_pair(pr, nr, points[i].xyz, normals[i].xyz, q, &alpha);
    keys[(size_t)r * n + i] = key;
    alphas[(size_t)r * n + i] = alpha;
  }
}
