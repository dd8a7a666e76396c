// Plain C++ references of single kernel steps (one function per __kernel of a multi-kernel
// routine whose whole-routine reference lives in host/), and the small helpers the per-kernel
// tests (tests/test_kernels_*.cpp) share: buffers with a guard tail, bin-edge checks of point
// pair features, random point images. Each reference repeats its kernel's float operations in
// the same order (the kernels are compiled with FP_CONTRACT OFF), so integer outputs and most
// float outputs must agree bit for bit. Header-only: nothing here is linked into binpick.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include "host/runtime/cl/cl_buffer.hpp"
#include "host/train/ppf_features.hpp"
#include "host/train/voxel_subsample.hpp"
#include "host/detect/scene/depth_to_points.hpp"
#include "host/detect/vote/ppf_vote.hpp"
#include "kernels/binpick_shared.h"
#include "kernels/scene_shared.h"

namespace binpick::test {

using u32 = std::uint32_t;

// ---- device helpers ---------------------------------------------------------------------------

// A device buffer holding `data` followed by `guard` copies of `canary`: a kernel that writes past
// the elements it owns changes the tail, which expect_guard_intact reports.
template <class T>
ocl::Buffer<T> guarded_buffer(ocl::Device& dev, std::vector<T> data, std::size_t guard,
                              const T& canary) {
  data.insert(data.end(), guard, canary);
  return ocl::Buffer<T>(dev, std::span<const T>(data));
}

template <class T>
ocl::Buffer<T> upload(ocl::Device& dev, const std::vector<T>& data) {
  return ocl::Buffer<T>(dev, std::span<const T>(data));
}

// Bit equality of floats (a -0 is not a +0, NaN equals itself).
inline bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// ---- device_scan.cl ------------------------------------------------------------------------------

// scan_chunks: out[i] = sum of in[begin(i's chunk) .. i), sums[b] = total of chunk b (0 for a
// chunk that starts at or after n). out has n values, sums `blocks`.
struct ScanChunksResult {
  std::vector<u32> out, sums;
};
inline ScanChunksResult scan_chunks_reference(const std::vector<u32>& in, u32 chunk, u32 blocks) {
  const std::size_t n = in.size();
  ScanChunksResult r{std::vector<u32>(n, 0), std::vector<u32>(blocks, 0)};
  for (u32 b = 0; b < blocks; ++b) {
    u32 sum = 0;
    for (std::size_t i = std::size_t(b) * chunk; i < std::min<std::size_t>(n, std::size_t(b + 1) * chunk); ++i) {
      r.out[i] = sum;
      sum += in[i];
    }
    r.sums[b] = sum;
  }
  return r;
}

// scan_chunk_sums: sums[0..blocks) becomes exclusive, sums[blocks] and out[n] the total.
inline void scan_chunk_sums_reference(std::vector<u32>& sums, u32 blocks, std::vector<u32>& out,
                                      u32 n) {
  u32 sum = 0;
  for (u32 b = 0; b < blocks; ++b) {
    const u32 v = sums[b];
    sums[b] = sum;
    sum += v;
  }
  sums[blocks] = sum;
  out[n] = sum;
}

// scan_add_offsets: out[i] += sums[i / chunk] for i < n.
inline void scan_add_offsets_reference(std::vector<u32>& out, u32 n, u32 chunk,
                                       const std::vector<u32>& sums) {
  for (u32 i = 0; i < n; ++i) out[i] += sums[i / chunk];
}

// ---- voxel_subsample.cl -----------------------------------------------------------------------

inline constexpr u32 kNoVoxelValue = 0xffffffffu;  // the fill of best_dist and best_index

// voxel_best_distance: the cell of each point and the bits of its squared distance to the cell's
// centre (voxel units), and per cell the smallest of those bits (kNoVoxelValue if empty).
struct VoxelDistances {
  std::vector<u32> cell_of, dist_bits, best_dist;
};
inline VoxelDistances voxel_best_distance_reference(const std::vector<Eigen::Vector3f>& points,
                                                    const VoxelGrid& g) {
  VoxelDistances r{{}, {}, std::vector<u32>(g.cells(), kNoVoxelValue)};
  for (const Eigen::Vector3f& p : points) {
    float f[3], d2 = 0;
    u32 c[3];
    for (int a = 0; a < 3; ++a) {
      f[a] = (p[a] - g.origin[a]) * g.inv_voxel;
      c[a] = std::min(static_cast<u32>(std::floor(f[a])), g.dims[a] - 1u);
    }
    const float dx = f[0] - (float(c[0]) + 0.5f), dy = f[1] - (float(c[1]) + 0.5f),
                dz = f[2] - (float(c[2]) + 0.5f);
    d2 = dx * dx + dy * dy + dz * dz;
    const u32 cell = (c[2] * g.dims[1] + c[1]) * g.dims[0] + c[0];
    u32 bits;
    std::memcpy(&bits, &d2, sizeof bits);
    r.cell_of.push_back(cell);
    r.dist_bits.push_back(bits);
    r.best_dist[cell] = std::min(r.best_dist[cell], bits);
  }
  return r;
}

// voxel_best_index: per cell the lowest index among the points at the cell's best distance.
inline std::vector<u32> voxel_best_index_reference(const std::vector<u32>& cell_of,
                                                   const std::vector<u32>& dist_bits,
                                                   const std::vector<u32>& best_dist) {
  std::vector<u32> best(best_dist.size(), kNoVoxelValue);
  for (u32 i = 0; i < cell_of.size(); ++i)
    if (dist_bits[i] == best_dist[cell_of[i]]) best[cell_of[i]] = std::min(best[cell_of[i]], i);
  return best;
}

// voxel_keep_flags: keep[i] = 1 if point i is its cell's chosen point.
inline std::vector<u32> voxel_keep_flags_reference(const std::vector<u32>& cell_of,
                                                   const std::vector<u32>& best_index) {
  std::vector<u32> keep(cell_of.size());
  for (u32 i = 0; i < cell_of.size(); ++i) keep[i] = best_index[cell_of[i]] == i ? 1u : 0u;
  return keep;
}

// voxel_compact: kept[position[i]] = i for every flagged i; `kept` starts as `initial`.
inline std::vector<u32> voxel_compact_reference(const std::vector<u32>& keep,
                                                const std::vector<u32>& position,
                                                std::vector<u32> initial) {
  for (u32 i = 0; i < keep.size(); ++i)
    if (keep[i]) initial[position[i]] = i;
  return initial;
}

// ---- ppf_table.cl -----------------------------------------------------------------------------

// The rows [g * rows_per_group, min(n, (g + 1) * rows_per_group)) of group g.
inline std::pair<std::size_t, std::size_t> group_rows(std::size_t g, std::size_t rows_per_group,
                                                      std::size_t n) {
  const std::size_t begin = g * rows_per_group;
  return {begin, std::max(begin, std::min(n, begin + rows_per_group))};
}

// ppf_count: counts[g * n_keys + key] = pairs (r, i), r in group g, with that key; keys is the
// row-major n x n key matrix of the pairs (BP_PPF_NO_KEY: not counted).
inline std::vector<u32> ppf_count_reference(const std::vector<u32>& keys, std::size_t n,
                                            u32 rows_per_group, u32 groups, u32 n_keys) {
  std::vector<u32> counts(std::size_t(groups) * n_keys, 0);
  for (u32 g = 0; g < groups; ++g) {
    const auto [begin, end] = group_rows(g, rows_per_group, n);
    for (std::size_t r = begin; r < end; ++r)
      for (std::size_t i = 0; i < n; ++i) {
        const u32 key = keys[r * n + i];
        if (i != r && key != BP_PPF_NO_KEY) ++counts[std::size_t(g) * n_keys + key];
      }
  }
  return counts;
}

// ppf_bucket_totals: totals[key] = sum over groups of counts[g * n_keys + key].
inline std::vector<u32> ppf_bucket_totals_reference(const std::vector<u32>& counts, u32 groups,
                                                    u32 n_keys) {
  std::vector<u32> totals(n_keys, 0);
  for (u32 g = 0; g < groups; ++g)
    for (u32 k = 0; k < n_keys; ++k) totals[k] += counts[std::size_t(g) * n_keys + k];
  return totals;
}

// ppf_group_slots: counts[g * n_keys + key] becomes offsets[key] + the counts of the groups
// before g in that bucket.
inline std::vector<u32> ppf_group_slots_reference(std::vector<u32> counts, u32 groups, u32 n_keys,
                                                  const std::vector<u32>& offsets) {
  for (u32 k = 0; k < n_keys; ++k) {
    u32 slot = offsets[k];
    for (u32 g = 0; g < groups; ++g) {
      u32& c = counts[std::size_t(g) * n_keys + k];
      const u32 here = c;
      c = slot;
      slot += here;
    }
  }
  return counts;
}

// ppf_scatter: group g writes the entries of its rows, in (r, i) order, at its slots (which it
// advances: on return slots holds each group's end in each bucket). pair_of[e] = r * n + i of the
// pair written to entry e (for checks against per-pair references).
struct PpfScatterResult {
  std::vector<bp_ppf_entry> entries;
  std::vector<std::size_t> pair_of;
  std::vector<u32> slots_after;
};
inline PpfScatterResult ppf_scatter_reference(const std::vector<u32>& keys,
                                              const std::vector<float>& alphas, std::size_t n,
                                              u32 rows_per_group, u32 groups, u32 n_keys,
                                              std::vector<u32> slots, std::size_t total) {
  PpfScatterResult r{std::vector<bp_ppf_entry>(total, bp_ppf_entry{0, 0.0f}),
                     std::vector<std::size_t>(total, 0), {}};
  for (u32 g = 0; g < groups; ++g) {
    const auto [begin, end] = group_rows(g, rows_per_group, n);
    for (std::size_t row = begin; row < end; ++row)
      for (std::size_t i = 0; i < n; ++i) {
        const u32 key = keys[row * n + i];
        if (i == row || key == BP_PPF_NO_KEY) continue;
        const u32 e = slots[std::size_t(g) * n_keys + key]++;
        r.entries[e] = {u32(row), alphas[row * n + i]};
        r.pair_of[e] = row * n + i;
      }
  }
  r.slots_after = std::move(slots);
  return r;
}

// ---- ppf_vote.cl ------------------------------------------------------------------------------

// ppf_peaks of one accumulator row: the k cells with the most votes (ties: the lower cell), of
// those with at least one vote, kept if votes >= peak_ratio * best (the kernel's float product);
// (cell, votes), and (0, 0) for every slot not kept.
// With n_alpha > 0, only cells that are local maxima along alpha (is_alpha_local_max) count.
inline std::vector<std::pair<u32, u32>> ppf_peaks_reference(std::span<const u32> acc, u32 k,
                                                            float peak_ratio, u32 n_alpha = 0) {
  std::vector<u32> order;
  for (u32 c = 0; c < acc.size(); ++c)
    if (acc[c] > 0 && (n_alpha == 0 || is_alpha_local_max(acc, c, n_alpha))) order.push_back(c);
  std::stable_sort(order.begin(), order.end(), [&](u32 a, u32 b) { return acc[a] > acc[b]; });
  std::vector<std::pair<u32, u32>> out(k, {0u, 0u});
  if (order.empty()) return out;
  const float threshold = peak_ratio * float(acc[order[0]]);
  for (u32 j = 0; j < std::min<std::size_t>(k, order.size()); ++j)
    if (float(acc[order[j]]) >= threshold) out[j] = {order[j], acc[order[j]]};
  return out;
}

// ---- scene_crop.cl ----------------------------------------------------------------------------

// The crop predicate of crop_count/crop_scatter (p, nrm: 4 floats; w = 0: no data).
inline bool crop_keeps_reference(const float* p, const float* nrm, const Eigen::Vector3f& centre,
                                 float radius2, bool require_normal) {
  if (p[3] == 0.0f) return false;
  if (require_normal && nrm[3] == 0.0f) return false;
  return bp_dist2(p[0], p[1], p[2], centre.x(), centre.y(), centre.z()) <= radius2;
}

// crop_count: per chunk g (pixels [g * chunk, min(n, (g + 1) * chunk))) the kept pixels.
inline std::vector<u32> crop_count_reference(const std::vector<float>& points,
                                             const std::vector<float>& normals, std::size_t n,
                                             u32 chunk, u32 chunks, const Eigen::Vector3f& centre,
                                             float radius2, bool require_normal) {
  std::vector<u32> counts(chunks, 0);
  for (u32 g = 0; g < chunks; ++g)
    for (std::size_t i = std::size_t(g) * chunk; i < std::min<std::size_t>(n, std::size_t(g + 1) * chunk); ++i)
      counts[g] += crop_keeps_reference(&points[4 * i], &normals[4 * i], centre, radius2, require_normal);
  return counts;
}

// crop_scatter: chunk g writes its kept points and normals (float4 each) from offsets[g] on,
// into out_points / out_normals (given as their initial contents).
inline void crop_scatter_reference(const std::vector<float>& points,
                                   const std::vector<float>& normals, std::size_t n, u32 chunk,
                                   u32 chunks, const Eigen::Vector3f& centre, float radius2,
                                   bool require_normal, const std::vector<u32>& offsets,
                                   std::vector<float>& out_points, std::vector<float>& out_normals) {
  for (u32 g = 0; g < chunks; ++g) {
    std::size_t o = offsets[g];
    for (std::size_t i = std::size_t(g) * chunk; i < std::min<std::size_t>(n, std::size_t(g + 1) * chunk); ++i)
      if (crop_keeps_reference(&points[4 * i], &normals[4 * i], centre, radius2, require_normal)) {
        std::copy_n(&points[4 * i], 4, &out_points[4 * o]);
        std::copy_n(&normals[4 * i], 4, &out_normals[4 * o]);
        ++o;
      }
  }
}

// crop_rect_count: per row of the rectangle {x0, y0, x1, y1} (half-open) the pixels with data
// whose point lies in the sphere.
inline bool crop_rect_keeps_reference(const float* p, const Eigen::Vector3f& centre, float radius2) {
  return p[3] != 0.0f && bp_dist2(p[0], p[1], p[2], centre.x(), centre.y(), centre.z()) <= radius2;
}
inline std::vector<u32> crop_rect_count_reference(const std::vector<float>& points, u32 width,
                                                  const std::array<u32, 4>& rect,
                                                  const Eigen::Vector3f& centre, float radius2) {
  std::vector<u32> counts(rect[3] - rect[1], 0);
  for (u32 g = 0; g < counts.size(); ++g)
    for (u32 x = rect[0]; x < rect[2]; ++x)
      counts[g] += crop_rect_keeps_reference(&points[4 * (std::size_t(rect[1] + g) * width + x)],
                                             centre, radius2);
  return counts;
}

// crop_rect_scatter: row g writes its kept pixel indices and points from offsets[g] on.
inline void crop_rect_scatter_reference(const std::vector<float>& points, u32 width,
                                        const std::array<u32, 4>& rect,
                                        const Eigen::Vector3f& centre, float radius2,
                                        const std::vector<u32>& offsets,
                                        std::vector<u32>& out_pixels,
                                        std::vector<float>& out_points) {
  for (u32 g = 0; g < rect[3] - rect[1]; ++g) {
    std::size_t o = offsets[g];
    for (u32 x = rect[0]; x < rect[2]; ++x) {
      const std::size_t i = std::size_t(rect[1] + g) * width + x;
      if (!crop_rect_keeps_reference(&points[4 * i], centre, radius2)) continue;
      out_pixels[o] = u32(i);
      std::copy_n(&points[4 * i], 4, &out_points[4 * o]);
      ++o;
    }
  }
}

// Exclusive prefix sum (the host's scan of the chunk counts in the crop routines).
inline std::vector<u32> exclusive_offsets(const std::vector<u32>& counts, u32* total = nullptr) {
  std::vector<u32> out(counts.size());
  u32 sum = 0;
  for (std::size_t i = 0; i < counts.size(); ++i) out[i] = sum, sum += counts[i];
  if (total) *total = sum;
  return out;
}

// ---- hypotheses.cl ----------------------------------------------------------------------

// hyp_chunk_argmin: per chunk the valid (> 0), not excluded pixel of smallest filtered depth
// (first in pixel order among equals): (INFINITY, BP_NO_PIXEL) if none.
struct ChunkArgmin {
  std::vector<float> depth;
  std::vector<u32> pixel;
};
inline ChunkArgmin hyp_chunk_argmin_reference(const std::vector<float>& filtered,
                                              const std::vector<std::uint8_t>& excluded,
                                              u32 chunk, u32 chunks) {
  const std::size_t n = filtered.size();
  ChunkArgmin r{std::vector<float>(chunks, INFINITY), std::vector<u32>(chunks, BP_NO_PIXEL)};
  for (u32 g = 0; g < chunks; ++g)
    for (std::size_t i = std::size_t(g) * chunk; i < std::min<std::size_t>(n, std::size_t(g + 1) * chunk); ++i)
      if (filtered[i] > 0.0f && !excluded[i] && filtered[i] < r.depth[g])
        r.depth[g] = filtered[i], r.pixel[g] = u32(i);
  return r;
}

// hyp_select: the best of the chunks or tiles (the smaller pixel among equal depths: for
// chunks in pixel order the first chunk), with the point on its pixel's
// ray at the filtered depth; all zero but pixel = BP_NO_PIXEL if no chunk has one.
inline bp_hypothesis hyp_select_reference(const std::vector<float>& part_depth,
                                          const std::vector<u32>& part_pixel,
                                          const std::vector<float>& points,
                                          const std::vector<float>& filtered, u32 width) {
  float best = INFINITY;
  u32 best_i = BP_NO_PIXEL;
  for (std::size_t g = 0; g < part_pixel.size(); ++g) {
    if (part_pixel[g] == BP_NO_PIXEL) continue;
    if (part_depth[g] < best || (part_depth[g] == best && part_pixel[g] < best_i))
      best = part_depth[g], best_i = part_pixel[g];
  }
  bp_hypothesis h{best_i, 0, 0, 0.0f, 0.0f, 0.0f, 0.0f, {0, 0}};
  if (best_i != BP_NO_PIXEL) {
    const float* p = &points[4 * std::size_t(best_i)];
    const float s = filtered[best_i] / p[2];
    h.u = best_i % width;
    h.v = best_i / width;
    h.depth = filtered[best_i];
    h.x = p[0] * s;
    h.y = p[1] * s;
    h.z = h.depth;
  }
  return h;
}

// hyp_exclude: flags the hypothesis' own pixel and every pixel with data within the radius of
// its point; nothing for BP_NO_PIXEL.
inline void hyp_exclude_reference(const std::vector<float>& points, const bp_hypothesis& h,
                                  float radius2, std::vector<std::uint8_t>& excluded) {
  if (h.pixel == BP_NO_PIXEL) return;
  for (std::size_t i = 0; i < excluded.size(); ++i) {
    const float* p = &points[4 * i];
    if (i == h.pixel || (p[3] != 0.0f && bp_dist2(p[0], p[1], p[2], h.x, h.y, h.z) <= radius2))
      excluded[i] = 1;
  }
}

// ---- scene_lowpass.cl -------------------------------------------------------------------------

// lowpass_pairs(_masked): per pixel (z, 1) where it has data (and the mask, if any, keeps it),
// else (0, 0), 2 floats.
inline std::vector<float> lowpass_pairs_reference(const std::vector<float>& points,
                                                  const std::vector<std::uint8_t>* mask = nullptr) {
  const std::size_t n = points.size() / 4;
  std::vector<float> out(2 * n, 0.0f);
  for (std::size_t i = 0; i < n; ++i)
    if (points[4 * i + 3] != 0.0f && (!mask || (*mask)[i] != 0))
      out[2 * i] = points[4 * i + 2], out[2 * i + 1] = 1.0f;
  return out;
}

// lowpass_rows (on the pairs): per pixel (sum of z, count) of the valid pixels in its row
// window, 2 floats.
inline std::vector<float> lowpass_rows_reference(const std::vector<float>& points, int width,
                                                 int height, int radius) {
  std::vector<float> out(2 * std::size_t(width) * height);
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) {
      float sum = 0.0f, count = 0.0f;
      for (int x = std::max(u - radius, 0); x <= std::min(u + radius, width - 1); ++x) {
        const float* p = &points[4 * (std::size_t(v) * width + x)];
        if (p[3] == 0.0f) continue;
        sum += p[2];
        count += 1.0f;
      }
      out[2 * (std::size_t(v) * width + u)] = sum;
      out[2 * (std::size_t(v) * width + u) + 1] = count;
    }
  return out;
}

// lowpass_cols: per valid pixel the column sum of the row sums over the column count; 0 where
// the pixel has no data.
inline std::vector<float> lowpass_cols_reference(const std::vector<float>& points,
                                                 const std::vector<float>& row_sums, int width,
                                                 int height, int radius) {
  std::vector<float> out(std::size_t(width) * height, 0.0f);
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) {
      const std::size_t i = std::size_t(v) * width + u;
      if (points[4 * i + 3] == 0.0f) continue;
      float sum = 0.0f, count = 0.0f;
      for (int y = std::max(v - radius, 0); y <= std::min(v + radius, height - 1); ++y) {
        sum += row_sums[2 * (std::size_t(y) * width + u)];
        count += row_sums[2 * (std::size_t(y) * width + u) + 1];
      }
      out[i] = sum / count;
    }
  return out;
}

// ---- scene_normals.cl -------------------------------------------------------------------------

// Eigenvalues (ascending) of the window covariance of pixel (u, v) as
// normals_from_points_reference forms it (double), to tell an ill-conditioned pixel: the two
// smallest nearly equal (the normal's direction is undetermined) or the middle one near the
// degeneracy threshold. Zero if fewer than 3 neighbours count.
inline Eigen::Vector3d normal_window_eigenvalues(const PointImage& pts, int u, int v, int radius,
                                                 float max_distance, int step = 1) {
  const float* c = &pts.xyzw[4 * (std::size_t(v) * pts.width + u)];
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sq = Eigen::Matrix3d::Zero();
  int n = 0;
  for (int y = v - radius; y <= v + radius; y += step)
    for (int x = u - radius; x <= u + radius; x += step) {
      if (x < 0 || y < 0 || x >= int(pts.width) || y >= int(pts.height)) continue;
      const float* p = &pts.xyzw[4 * (std::size_t(y) * pts.width + x)];
      if (p[3] == 0 || bp_dist2(p[0], p[1], p[2], c[0], c[1], c[2]) > max_distance * max_distance)
        continue;
      const Eigen::Vector3d q(double(p[0]) - c[0], double(p[1]) - c[1], double(p[2]) - c[2]);
      sum += q, sq += q * q.transpose(), ++n;
    }
  if (n < 3) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d m = sum / n;
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(sq / n - m * m.transpose()).eigenvalues();
}

// ---- point pair features: discretisation edges ------------------------------------------------

inline float circular_distance(float a, float b) {
  const float d = std::fabs(a - b);
  return std::min(d, 2 * std::numbers::pi_v<float> - d);
}

// Whether value lies within eps of an edge between two of `bins` bins of width step starting at
// 0 (k * step for k in 1 .. bins - 1): where rounding may move it to the neighbouring bin. The
// outer edges are no such place: bp_quantize clamps below 0 and above the last bin.
inline bool near_bin_edge(float value, float step, u32 bins, float eps) {
  const float r = value / step, k = std::round(r);
  return k >= 1.0f && k <= float(bins) - 1.0f && std::fabs(r - k) * step <= eps;
}

// Rounding allowed at a bin edge: angles are computed with bp_atan2_8 (to ~2e-7 rad) on the
// device and std::atan2 in the reference, each from float cross and dot products; distances
// with a different summation order.
inline constexpr float kAngleEdgeEps = 1e-4f;      // rad
inline constexpr float kDistanceEdgeRel = 1e-5f;   // of max_distance

// Whether feature f (the Eigen reference of a pair) lies next to an edge of the discretisation:
// between two distance bins, at the max_distance / min-distance cut-offs, or between two angle
// bins. Such a pair may get
// a different key (or none) on the device.
inline bool ppf_feature_near_edge(const PairFeature& f, const bp_ppf_quant& q) {
  const float de = kDistanceEdgeRel * q.max_distance;
  if (std::fabs(f.f[0] - q.max_distance) <= de) return true;
  if (std::fabs(f.f[0] - BP_PPF_MIN_DIST_RATIO * q.max_distance) <= de) return true;
  if (!f.valid) return false;
  if (near_bin_edge(f.f[0], q.dist_step, q.n_dist, de)) return true;
  for (int a = 1; a < 4; ++a)
    if (near_bin_edge(f.f[a], q.angle_step, q.n_angle, kAngleEdgeEps)) return true;
  return false;
}

// Whether the keys got (device) and want (reference feature f) differ only in components whose
// value lies next to a bin edge (or in the key's presence at a cut-off).
inline bool ppf_key_difference_at_edge(u32 got, const PairFeature& f, const bp_ppf_quant& q) {
  const u32 want = f.key;
  if (got == want) return true;
  const float de = kDistanceEdgeRel * q.max_distance;
  if (got == BP_PPF_NO_KEY || want == BP_PPF_NO_KEY)
    return std::fabs(f.f[0] - q.max_distance) <= de ||
           std::fabs(f.f[0] - BP_PPF_MIN_DIST_RATIO * q.max_distance) <= de;
  u32 a[4], b[4];  // d, a1, a2, a3
  for (auto [key, out] : {std::pair{got, a}, std::pair{want, b}}) {
    out[3] = key % q.n_angle, key /= q.n_angle;
    out[2] = key % q.n_angle, key /= q.n_angle;
    out[1] = key % q.n_angle, out[0] = key / q.n_angle;
  }
  if (a[0] != b[0] && !near_bin_edge(f.f[0], q.dist_step, q.n_dist, de)) return false;
  for (int c = 1; c < 4; ++c)
    if (a[c] != b[c] && !near_bin_edge(f.f[c], q.angle_step, q.n_angle, kAngleEdgeEps)) return false;
  return true;
}

// ---- random test data -------------------------------------------------------------------------

// Camera-frame points of a random smooth surface seen by a pinhole camera of focal length f
// (centred): a tilted plane at 600-900 mm with a few Gaussian bumps, Gaussian depth noise of
// `noise` mm, and each pixel without data (all 0) with probability `holes`.
inline PointImage random_point_image(std::mt19937& rng, u32 width, u32 height, float holes,
                                     float noise = 0.5f, float focal = 150.0f) {
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  std::normal_distribution<float> N(0.0f, 1.0f);
  const float base = 600.0f + 300.0f * U(rng), gx = U(rng) - 0.5f, gy = U(rng) - 0.5f;
  struct Bump { float u, v, s, h; };
  std::vector<Bump> bumps;
  for (int b = int(4 * U(rng)); b > 0; --b)
    bumps.push_back({U(rng) * width, U(rng) * height, 2.0f + 0.2f * (width + height) * U(rng),
                     -150.0f * U(rng)});
  const float cx = (width - 1) / 2.0f, cy = (height - 1) / 2.0f;
  PointImage img{width, height, std::vector<float>(4 * std::size_t(width) * height, 0.0f)};
  for (u32 v = 0; v < height; ++v)
    for (u32 u = 0; u < width; ++u) {
      if (U(rng) < holes) continue;
      float z = base + gx * (float(u) - cx) + gy * (float(v) - cy);
      for (const Bump& b : bumps) {
        const float r2 = ((u - b.u) * (u - b.u) + (v - b.v) * (v - b.v)) / (b.s * b.s);
        z += b.h * std::exp(-r2);
      }
      z += noise * N(rng);
      float* p = &img.xyzw[4 * (std::size_t(v) * width + u)];
      p[0] = (float(u) - cx) * z / focal;
      p[1] = (float(v) - cy) * z / focal;
      p[2] = z;
      p[3] = 1.0f;
    }
  return img;
}

}  // namespace binpick::test
