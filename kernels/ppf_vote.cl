/* Drost voting around one hypothesis (paper section III-B).
 *
 * ppf_scene_features: one work item per reference point s_r; for every subsampled scene point
 *   s_i the key and alpha_s of the pair (s_r, s_i), computed by the same bp_ppf_pair8 as the
 *   model (so model and scene features cannot drift apart). Row r of keys/alphas is s_r's.
 * ppf_vote: one work item per reference point, with its own accumulator of n_model x n_alpha
 *   integer counters in global memory (no atomics, so the votes are exact and deterministic).
 *   Every model entry (m_r, alpha_m) of the pair's key votes for (m_r, alpha_s - alpha_m),
 *   read as bp_vote_entry (binpick_shared.h: worked out at upload, the same arithmetic as the
 *   reference's, so both count the same votes).
 *   Duplicate votes (Hinterstoisser et al. 2016): two scene points that give a reference point
 *   the same key and the same alpha_s bin vote for the same cells, and a flat or repeated
 *   surface gives thousands of such equal pairs (a plane outvotes the part beside it). With
 *   `unique` set, only the first of them in row order votes: `seen` holds per work item an
 *   open-addressing set of (key, alpha_s bin) with `slots` entries (a power of two > 2 n, so
 *   it never fills).
 * ppf_peaks: one work item per reference point; the `k` best accumulator cells, highest votes
 *   first (ties: lowest cell index), that have at least peak_ratio of the best cell's votes
 *   (and with local_max, that are local maxima along alpha: alpha_local_max).
 *   Several peaks per reference point, not only the maximum: a symmetric or partly occluded
 *   part has several near-equal poses, and the clustering decides between them.
 *
 * Why alpha_s - alpha_m: with R_m and R_s the rotations that take n_m and n_s onto +x, the
 * features give R_m d_m = R_x(alpha_m) v and R_s d_s = R_x(alpha_s) v for the same v, so the
 * rotation about x that maps the model pair onto the scene pair is R_x(alpha_s - alpha_m), and
 * the pose is s = R_s^T R_x(alpha_s - alpha_m) R_m (m - m_r) + s_r. */
#pragma OPENCL FP_CONTRACT OFF
#include "binpick_shared.h"

__kernel void ppf_scene_features(__global const float4* points, __global const float4* normals,
                                 const uint n, __global const uint* refs, const uint n_refs,
                                 const bp_ppf_quant q, __global uint* keys,
                                 __global float* alphas) {
  const uint r = get_global_id(0);
  if (r >= n_refs) return;
  const uint ref = refs[r];
  const float3 pr = points[ref].xyz;
  const float3 nr = normals[ref].xyz;
  for (uint i = 0; i < n; i += 8u) {
    float8 alpha;
    const uint8 key = bp_ppf_pairs_at(pr, nr, points, normals, i, n, ref, q, &alpha);
    bp_store8(key, keys + (size_t)r * n + i, n - i);
    bp_store8(as_uint8(alpha), (__global uint*)alphas + (size_t)r * n + i, n - i);
  }
}

/* Rows first_ref .. first_ref + count - 1 of the features vote into accumulator slices
 * 0 .. count - 1 (a batch: the accumulators of all reference points may not fit at once). */
#define PPF_SEEN_EMPTY 0xffffffffffffffffUL

/* Inserts v into the set; false if it was there already. */
static inline bool seen_insert(__global ulong* seen, const uint slots, const ulong v) {
  uint h = (uint)((v * 0x9E3779B97F4A7C15UL) >> 32) & (slots - 1u);
  for (;;) {
    const ulong s = seen[h];
    if (s == v) return false;
    if (s == PPF_SEEN_EMPTY) {
      seen[h] = v;
      return true;
    }
    h = (h + 1u) & (slots - 1u);
  }
}

__kernel void ppf_vote(__global const uint* keys, __global const float* alphas, const uint n,
                       const uint first_ref, const uint count,
                       __global const uint* offsets, __global const bp_vote_entry* entries,
                       const uint n_model, const bp_ppf_quant q, const float inv_step,
                       __global uint* accumulators, const uint unique, __global ulong* seen_sets,
                       const uint slots, const uint spread) {
  const uint r = get_global_id(0);
  if (r >= count) return;
  const uint cells = n_model * q.n_alpha;
  __global uint* acc = accumulators + (size_t)r * cells;
  for (uint c = 0; c < cells; ++c) acc[c] = 0u;
  __global ulong* seen = seen_sets + (size_t)r * slots;
  if (unique)
    for (uint c = 0; c < slots; ++c) seen[c] = PPF_SEEN_EMPTY;
  __global const uint* row_keys = keys + (size_t)(first_ref + r) * n;
  __global const float* row_alphas = alphas + (size_t)(first_ref + r) * n;
  for (uint i = 0; i < n; ++i) {
    const uint key = row_keys[i];
    if (key == BP_PPF_NO_KEY) continue;
    const float alpha_s = row_alphas[i];
    if (unique &&
        !seen_insert(seen, slots,
                     (ulong)key * q.n_alpha + bp_alpha_s_bin(alpha_s, inv_step, q.n_alpha)))
      continue;
    const float scaled_s = alpha_s * inv_step;
    const uint end = offsets[key + 1];
    /* Two loops, the choice made once per pair: a branch inside the hot loop cost more than
     * the second increment itself. */
    float frac;
    if (spread) {
      for (uint e = offsets[key]; e < end; ++e) {
        const bp_vote_entry entry = entries[e];
        __global uint* row = acc + entry.row;
        const uint b = bp_vote_bin(scaled_s, entry.offset, q.n_alpha, &frac);
        ++row[b];
        ++row[bp_vote_neighbour(b, frac, q.n_alpha)];
      }
    } else {
      for (uint e = offsets[key]; e < end; ++e) {
        const bp_vote_entry entry = entries[e];
        ++acc[entry.row + bp_vote_bin(scaled_s, entry.offset, q.n_alpha, &frac)];
      }
    }
  }
}

#define PPF_MAX_PEAKS 16

/* Whether cell c (votes v) is at least as high as its two alpha neighbours (the row of its model
 * point wraps around the full turn). One peak spread over two bins is then taken once, and the
 * other peaks kept are other poses. */
static inline bool alpha_local_max(__global const uint* acc, const uint c, const uint v,
                                   const uint n_alpha) {
  if (n_alpha < 2u) return true;
  const uint b = c % n_alpha, row = c - b;
  const uint l = row + (b == 0u ? n_alpha - 1u : b - 1u);
  const uint r = row + (b + 1u == n_alpha ? 0u : b + 1u);
  return v >= acc[l] && v >= acc[r];
}

/* peaks[(first_ref + r) * k + j] = (cell, votes), cell = model point * n_alpha + alpha bin;
 * votes 0 marks an unused slot. Ranking: more votes first, then the lower cell. */
__kernel void ppf_peaks(__global const uint* accumulators, const uint first_ref, const uint count,
                        const uint cells, const uint k, const float peak_ratio,
                        __global uint2* peaks, const uint n_alpha, const uint local_max) {
  const uint r = get_global_id(0);
  if (r >= count) return;
  __global const uint* acc = accumulators + (size_t)r * cells;
  uint best_cell[PPF_MAX_PEAKS], best_votes[PPF_MAX_PEAKS];
  for (uint j = 0; j < k; ++j) best_votes[j] = 0u, best_cell[j] = 0u;
  for (uint c = 0; c < cells; ++c) {
    const uint v = acc[c];
    if (v <= best_votes[k - 1]) continue; /* ties keep the earlier (lower) cell */
    if (local_max && !alpha_local_max(acc, c, v, n_alpha)) continue;
    uint j = k - 1;
    while (j > 0 && best_votes[j - 1] < v) {
      best_votes[j] = best_votes[j - 1];
      best_cell[j] = best_cell[j - 1];
      --j;
    }
    best_votes[j] = v;
    best_cell[j] = c;
  }
  /* The same float product on the host (ppf_peaks_reference), so both keep the same peaks. */
  const float threshold = peak_ratio * (float)best_votes[0];
  __global uint2* out = peaks + (size_t)(first_ref + r) * k;
  for (uint j = 0; j < k; ++j) {
    const bool keep = best_votes[j] > 0u && (float)best_votes[j] >= threshold;
    out[j] = (uint2)(keep ? best_cell[j] : 0u, keep ? best_votes[j] : 0u);
  }
}
