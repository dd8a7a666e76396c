/* The PPF hash table of a model, built on the device as CSR: offsets[key] .. offsets[key + 1]
 * index the entries (m_r, alpha_m) of every pair with that key; no pair is lost to a collision.
 *
 * Deterministic without atomics or sorting: the reference points are split into `groups`
 * consecutive blocks of rows, one work item each, and every group counts its pairs per key in
 * its own histogram (counts[g * n_keys + key]). The totals per key give the CSR offsets (an
 * exclusive scan, device_scan.cl); each group's slots in a bucket start after those of the groups
 * before it. A group then recomputes its features (cheaper than storing n^2 of them) and fills
 * its slots in row order, so entries within a bucket are ordered by (m_r, m_i), run to run. */
#pragma OPENCL FP_CONTRACT OFF
#include "binpick_shared.h"

__kernel void ppf_count(__global const float4* points, __global const float4* normals,
                        const uint n, const bp_ppf_quant q, const uint rows_per_group,
                        const uint n_keys, __global uint* counts) {
  const uint g = get_global_id(0);
  const uint begin = g * rows_per_group;
  const uint end = min(n, begin + rows_per_group);
  __global uint* histogram = counts + (size_t)g * n_keys;
  for (uint r = begin; r < end; ++r) {
    const float3 pr = points[r].xyz;
    const float3 nr = normals[r].xyz;
    for (uint i = 0; i < n; i += 8u) {
      float8 alpha;
      uint k[8];
      vstore8(bp_ppf_pairs_at(pr, nr, points, normals, i, n, r, q, &alpha), 0, k);
      for (uint l = 0; l < 8u; ++l)
        if (k[l] != BP_PPF_NO_KEY) ++histogram[k[l]];
    }
  }
}

/* totals[key] = pairs with that key over all groups. */
__kernel void ppf_bucket_totals(__global const uint* counts, const uint groups, const uint n_keys,
                                __global uint* totals) {
  const uint key = get_global_id(0);
  if (key >= n_keys) return;
  uint sum = 0u;
  for (uint g = 0; g < groups; ++g) sum += counts[(size_t)g * n_keys + key];
  totals[key] = sum;
}

/* counts[g * n_keys + key] becomes the first slot of group g in bucket key. */
__kernel void ppf_group_slots(__global uint* counts, const uint groups, const uint n_keys,
                              __global const uint* offsets) {
  const uint key = get_global_id(0);
  if (key >= n_keys) return;
  uint slot = offsets[key];
  for (uint g = 0; g < groups; ++g) {
    const size_t at = (size_t)g * n_keys + key;
    const uint c = counts[at];
    counts[at] = slot;
    slot += c;
  }
}

__kernel void ppf_scatter(__global const float4* points, __global const float4* normals,
                          const uint n, const bp_ppf_quant q, const uint rows_per_group,
                          const uint n_keys, __global uint* slots,
                          __global bp_ppf_entry* entries) {
  const uint g = get_global_id(0);
  const uint begin = g * rows_per_group;
  const uint end = min(n, begin + rows_per_group);
  __global uint* next = slots + (size_t)g * n_keys;
  for (uint r = begin; r < end; ++r) {
    const float3 pr = points[r].xyz;
    const float3 nr = normals[r].xyz;
    for (uint i = 0; i < n; i += 8u) {
      float8 alpha;
      uint k[8];
      float a[8];
      vstore8(bp_ppf_pairs_at(pr, nr, points, normals, i, n, r, q, &alpha), 0, k);
      vstore8(alpha, 0, a);
      for (uint l = 0; l < 8u; ++l) {
        if (k[l] == BP_PPF_NO_KEY) continue;
        bp_ppf_entry e;
        e.point = r;
        e.alpha = a[l];
        entries[next[k[l]]++] = e;
      }
    }
  }
}
