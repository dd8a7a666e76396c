#include "host/detect/vote/ppf_vote.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <set>
#include <numbers>
#include <span>
#include <string>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/core/cloud_input.hpp"
#include "host/train/ppf_bucket_cap.hpp"
#include "host/train/ppf_features.hpp"

namespace binpick {
namespace {

std::size_t cells_of(const PpfModel& model) {
  return model.cloud.points.size() * std::size_t(model.quant.n_alpha);
}

}  // namespace

DeviceModel upload_model(ocl::Device& dev, const PpfModel& model, std::size_t bucket_cap) {
  if (model.table.offsets.size() != std::size_t(bp_ppf_key_count(model.quant)) + 1)
    throw InputError("PPF model table does not match its discretisation");
  DeviceModel d;
  d.model = &model;
  d.bucket_cap = bucket_cap;
  // Copied only when capped (the tee's table holds 1.5 M entries).
  const PpfTable capped = bucket_cap == 0 ? PpfTable{} : cap_ppf_buckets(model.table, bucket_cap);
  const PpfTable& table = bucket_cap == 0 ? model.table : capped;
  d.offsets = ocl::Buffer<std::uint32_t>(dev, std::span<const std::uint32_t>(table.offsets),
                                         CL_MEM_READ_ONLY);
  const std::vector<bp_vote_entry> entries = vote_entries(table.entries, model.quant);
  d.entries = ocl::Buffer<bp_vote_entry>(dev, std::span<const bp_vote_entry>(entries),
                                         CL_MEM_READ_ONLY);
  return d;
}

std::vector<std::uint32_t> select_reference_points(std::size_t n, double ratio) {
  if (!(std::isfinite(ratio) && ratio > 0 && ratio <= 1))
    throw InputError(fmt::format("reference point ratio {} must be in (0, 1]", ratio));
  std::vector<std::uint32_t> refs;
  if (n == 0) return refs;
  const std::size_t m = std::clamp<std::size_t>(std::size_t(std::llround(ratio * double(n))), 1, n);
  refs.reserve(m);
  for (std::size_t j = 0; j < m; ++j) refs.push_back(static_cast<std::uint32_t>(j * n / m));
  return refs;
}

void check(const VoteOptions& opt) {
  if (opt.peaks_per_ref < 1 || opt.peaks_per_ref > 16)
    throw InputError(fmt::format("peaks per reference point {} must be in [1, 16]",
                                 opt.peaks_per_ref));
  if (!(opt.peak_ratio >= 0 && opt.peak_ratio <= 1))
    throw InputError(fmt::format("peak ratio {} must be in [0, 1]", opt.peak_ratio));
  if (opt.max_accumulator_cells == 0) throw InputError("accumulator budget must be positive");
}

std::vector<VotePeak> vote_peaks(ocl::Device& dev, const DeviceModel& dmodel,
                                 const PointCloud& input, const std::vector<std::uint32_t>& refs,
                                 const VoteOptions& opt, StageTimings* timings,
                                 ScenePairs* pairs_out) {
  check(opt);
  const PpfModel& model = *dmodel.model;
  const PointCloud scene = ppf_input(input, kMaxVoteScenePoints, "scene neighbourhood");
  const std::size_t n = scene.points.size();
  for (std::uint32_t r : refs)
    if (r >= n) throw InputError(fmt::format("reference point {} of {} points", r, n));
  const std::size_t n_refs = refs.size();
  const std::size_t cells = cells_of(model);
  std::vector<VotePeak> peaks;
  if (n_refs == 0 || n == 0 || cells == 0) return peaks;
  Stopwatch clock;

  ocl::Buffer<cl_float4> points(dev, std::span<const cl_float4>(pack_float4(scene.points)),
                                CL_MEM_READ_ONLY);
  ocl::Buffer<cl_float4> normals(dev, std::span<const cl_float4>(pack_float4(scene.normals)),
                                 CL_MEM_READ_ONLY);
  ocl::Buffer<std::uint32_t> ref_buf(dev, std::span<const std::uint32_t>(refs), CL_MEM_READ_ONLY);
  ocl::Buffer<std::uint32_t> keys(dev, n_refs * n);
  ocl::Buffer<float> alphas(dev, n_refs * n);
  const auto n32 = static_cast<std::uint32_t>(n), refs32 = static_cast<std::uint32_t>(n_refs);
  cl::Kernel features = dev.kernel("ppf_vote.cl", "ppf_scene_features");
  ocl::launch_tasks(dev, features, n_refs, points, normals, n32, ref_buf, refs32, model.quant, keys,
              alphas);
  ocl::finish(dev);
  if (timings) timings->push_back({"features", clock.lap()});

  // Batches of reference points whose accumulators fit the budget. Each work item clears its
  // own accumulator, so the buffer is reused without a fill.
  // The duplicate sets: a power of two above 2 n slots of 8 bytes each, per reference point.
  const std::size_t slots = opt.unique_votes ? std::bit_ceil(2 * n + 1) : 1;
  const std::size_t per_ref = cells + (opt.unique_votes ? 2 * slots : 0);
  const std::size_t batch = std::clamp<std::size_t>(opt.max_accumulator_cells / per_ref, 1, n_refs);
  ocl::Buffer<std::uint32_t> acc(dev, batch * cells);
  ocl::Buffer<cl_ulong> seen(dev, opt.unique_votes ? batch * slots : 1);
  const std::uint32_t k = opt.peaks_per_ref;
  ocl::Buffer<cl_uint2> peak_buf(dev, n_refs * k);
  cl::Kernel vote = dev.kernel("ppf_vote.cl", "ppf_vote");
  cl::Kernel find_peaks = dev.kernel("ppf_vote.cl", "ppf_peaks");
  const auto n_model = static_cast<std::uint32_t>(model.cloud.points.size());
  const auto cells32 = static_cast<std::uint32_t>(cells);
  double vote_ms = 0, peaks_ms = 0;
  for (std::size_t first = 0; first < n_refs; first += batch) {
    const auto count = static_cast<std::uint32_t>(std::min(batch, n_refs - first));
    const auto first32 = static_cast<std::uint32_t>(first);
    ocl::launch_tasks(dev, vote, count, keys, alphas, n32, first32, count, dmodel.offsets,
                dmodel.entries, n_model, model.quant, ppf_vote_inv_step(model.quant), acc,
                cl_uint(opt.unique_votes ? 1 : 0), seen, static_cast<std::uint32_t>(slots),
                cl_uint(opt.spread_alpha ? 1 : 0));
    ocl::finish(dev);
    vote_ms += clock.lap();
    ocl::launch_tasks(dev, find_peaks, count, acc, first32, count, cells32, k, opt.peak_ratio,
                      peak_buf, model.quant.n_alpha, cl_uint(opt.local_max ? 1 : 0));
    ocl::finish(dev);
    peaks_ms += clock.lap();
  }
  const std::vector<cl_uint2> raw = peak_buf.read(dev);
  const std::uint32_t n_alpha = model.quant.n_alpha;
  for (std::size_t i = 0; i < raw.size(); ++i)
    if (raw[i].s[1] > 0)
      peaks.push_back({static_cast<std::uint32_t>(i / k), raw[i].s[0] / n_alpha,
                       raw[i].s[0] % n_alpha, raw[i].s[1]});
  peaks_ms += clock.lap();
  if (timings) {
    timings->push_back({"vote", vote_ms});
    timings->push_back({"peaks", peaks_ms});
  }
  if (pairs_out) {
    pairs_out->n = n;
    pairs_out->refs = refs;
    pairs_out->keys = keys.read(dev);
    pairs_out->alphas = alphas.read(dev);
  }
  return peaks;
}

ScenePairs scene_pair_features_reference(const PointCloud& input,
                                         const std::vector<std::uint32_t>& refs,
                                         const bp_ppf_quant& quant) {
  const PointCloud scene = ppf_input(input, kMaxVoteScenePoints, "scene neighbourhood");
  ScenePairs pairs;
  pairs.n = scene.points.size();
  pairs.refs = refs;
  pairs.keys.assign(refs.size() * pairs.n, BP_PPF_NO_KEY);
  pairs.alphas.assign(refs.size() * pairs.n, 0.0f);
  for (std::size_t r = 0; r < refs.size(); ++r) {
    const std::uint32_t ref = refs.at(r);
    if (ref >= pairs.n) throw InputError(fmt::format("reference point {} of {} points", ref, pairs.n));
    for (std::size_t i = 0; i < pairs.n; ++i) {
      if (i == ref) continue;
      const PairFeature f =
          ppf_pair_feature_reference(scene.points[ref], scene.normals[ref], scene.points[i],
                                     scene.normals[i], quant);
      pairs.keys[r * pairs.n + i] = f.key;
      pairs.alphas[r * pairs.n + i] = f.valid ? f.alpha : 0.0f;
    }
  }
  return pairs;
}

float ppf_vote_inv_step(const bp_ppf_quant& quant) {
  return float(double(quant.n_alpha) / (2.0 * std::numbers::pi));
}

std::vector<bp_vote_entry> vote_entries(std::span<const bp_ppf_entry> entries,
                                        const bp_ppf_quant& quant) {
  const float inv_step = ppf_vote_inv_step(quant);
  std::vector<bp_vote_entry> out(entries.size());
  for (std::size_t e = 0; e < entries.size(); ++e)
    out[e] = {entries[e].point * quant.n_alpha,
              bp_vote_offset(entries[e].alpha, inv_step, quant.n_alpha)};
  return out;
}

std::uint32_t ppf_vote_alpha_bin(float alpha_s, float alpha_m, const bp_ppf_quant& quant,
                                 float* frac) {
  const float inv_step = ppf_vote_inv_step(quant);
  float unused = 0;
  return bp_vote_bin(alpha_s * inv_step, bp_vote_offset(alpha_m, inv_step, quant.n_alpha),
                     quant.n_alpha, frac ? frac : &unused);
}

std::uint32_t ppf_vote_alpha_neighbour(float alpha_s, float alpha_m, const bp_ppf_quant& quant) {
  float frac = 0;
  const std::uint32_t b = ppf_vote_alpha_bin(alpha_s, alpha_m, quant, &frac);
  return bp_vote_neighbour(b, frac, quant.n_alpha);
}

std::vector<std::uint32_t> vote_accumulator_reference(const ScenePairs& pairs, std::size_t r,
                                                      const PpfModel& model, bool unique_votes,
                                                      bool spread_alpha) {
  const std::uint32_t n_alpha = model.quant.n_alpha;
  std::vector<std::uint32_t> acc(cells_of(model), 0);
  std::set<std::pair<std::uint32_t, std::uint32_t>> seen;  // (key, alpha_s bin) that voted
  const float inv_step = ppf_vote_inv_step(model.quant);
  for (std::size_t i = 0; i < pairs.n; ++i) {
    const std::uint32_t key = pairs.keys[r * pairs.n + i];
    if (key == BP_PPF_NO_KEY) continue;
    const float alpha_s = pairs.alphas[r * pairs.n + i];
    if (unique_votes && !seen.insert({key, bp_alpha_s_bin(alpha_s, inv_step, n_alpha)}).second)
      continue;
    for (std::uint32_t e = model.table.offsets.at(key); e < model.table.offsets.at(key + 1); ++e) {
      const bp_ppf_entry& entry = model.table.entries[e];
      const std::size_t row = std::size_t(entry.point) * n_alpha;
      ++acc[row + ppf_vote_alpha_bin(alpha_s, entry.alpha, model.quant)];
      if (spread_alpha) ++acc[row + ppf_vote_alpha_neighbour(alpha_s, entry.alpha, model.quant)];
    }
  }
  return acc;
}

bool is_alpha_local_max(std::span<const std::uint32_t> acc, std::uint32_t c,
                        std::uint32_t n_alpha) {
  if (n_alpha < 2) return true;
  const std::uint32_t b = c % n_alpha, row = c - b;
  const std::uint32_t l = row + (b == 0 ? n_alpha - 1 : b - 1);
  const std::uint32_t r = row + (b + 1 == n_alpha ? 0 : b + 1);
  return acc[c] >= acc[l] && acc[c] >= acc[r];
}

std::vector<VotePeak> vote_peaks_reference(const ScenePairs& pairs, const PpfModel& model,
                                           const VoteOptions& opt) {
  check(opt);
  std::vector<VotePeak> peaks;
  const std::uint32_t n_alpha = model.quant.n_alpha;
  for (std::size_t r = 0; r < pairs.refs.size(); ++r) {
    const std::vector<std::uint32_t> acc =
        vote_accumulator_reference(pairs, r, model, opt.unique_votes, opt.spread_alpha);
    std::vector<std::uint32_t> order;
    for (std::uint32_t c = 0; c < acc.size(); ++c)
      if (acc[c] > 0 && (!opt.local_max || is_alpha_local_max(acc, c, n_alpha)))
        order.push_back(c);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return acc[a] > acc[b]; });
    if (order.empty()) continue;
    const float threshold = opt.peak_ratio * float(acc[order[0]]);
    for (std::size_t j = 0; j < std::min<std::size_t>(opt.peaks_per_ref, order.size()); ++j)
      if (float(acc[order[j]]) >= threshold)
        peaks.push_back({static_cast<std::uint32_t>(r), order[j] / n_alpha, order[j] % n_alpha,
                         acc[order[j]]});
  }
  return peaks;
}

}  // namespace binpick
