// Drost voting around one hypothesis (paper section III-B; kernels/ppf_vote.cl):
// the point pair features of every reference point with every other subsampled scene point,
// the hash lookup, one integer accumulator (model point x alpha bin) per reference point, and
// its peaks. A peak (s_r, m_r, alpha) is a candidate pose; ppf_pose.hpp turns it into one.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "host/runtime/cl/cl_buffer.hpp"
#include "host/core/timing.hpp"
#include "host/core/mesh.hpp"
#include "host/train/ppf_model.hpp"

namespace binpick {

// The model's hash table on the device, uploaded once per run (not once per hypothesis).
struct DeviceModel {
  const PpfModel* model = nullptr;  // must outlive this
  ocl::Buffer<std::uint32_t> offsets;
  ocl::Buffer<bp_vote_entry> entries;  // as the vote reads them (vote_entries)
  std::size_t bucket_cap = 0;       // entries a bucket keeps (cap_ppf_buckets); 0: all
};
// The table as cap_ppf_buckets(model.table, bucket_cap) leaves it (0: the whole table), its
// entries as vote_entries gives them.
DeviceModel upload_model(ocl::Device& dev, const PpfModel& model, std::size_t bucket_cap = 0);

// Reference points: m = max(1, round(ratio * n)) of n subsampled scene points, evenly spread
// over the cloud's order (index floor(j * n / m)): deterministic, and in pixel order this
// spreads them over the neighbourhood. Empty for n = 0. ratio in (0, 1].
std::vector<std::uint32_t> select_reference_points(std::size_t n, double ratio);

// The pair features of the reference points, row r = refs[r] against all n scene points.
struct ScenePairs {
  std::size_t n = 0;                  // scene points
  std::vector<std::uint32_t> refs;    // reference point indices into the scene cloud
  std::vector<std::uint32_t> keys;    // refs.size() * n, BP_PPF_NO_KEY for skipped pairs
  std::vector<float> alphas;          // refs.size() * n, alpha_s
};

struct VoteOptions {
  std::uint32_t peaks_per_ref = 3;  // accumulator peaks kept per reference point, in [1, 16]
  float peak_ratio = 0.9f;          // a peak needs at least this fraction of the best's votes
  // Scene pairs of one reference point with the same key and alpha_s bin vote once (the first
  // in row order; kernels/ppf_vote.cl says why). Off by default: it cost the bracket and the
  // shaft more than it gained the tee (docs/decisions/2026-11-24-unique-votes.md).
  bool unique_votes = false;
  // Every vote also goes to the alpha bin next to its own on the nearer side (kernels/ppf_vote.cl).
  // Off by default: voting becomes several times slower (docs/decisions/2026-11-24-spread-votes.md).
  bool spread_alpha = false;
  // Peaks must be local maxima along alpha (kernels/ppf_vote.cl alpha_local_max). The detector
  // turns it on (DetectParams::local_peaks; docs/decisions/2026-11-24-local-peaks.md); the
  // routine's default keeps Drost's best cells.
  bool local_max = false;
  // Accumulator counters (and duplicate sets, counted in the same 4-byte units) allocated at
  // once; reference points vote in batches that fit.
  std::size_t max_accumulator_cells = std::size_t(1) << 24;
};
void check(const VoteOptions& opt);

// A peak of reference point `ref` (index into ScenePairs::refs): the model point and alpha bin
// voted for, with its votes.
struct VotePeak {
  std::uint32_t ref = 0, model_point = 0, alpha_bin = 0, votes = 0;
  friend bool operator==(const VotePeak&, const VotePeak&) = default;
};

// Largest scene neighbourhood voted on (points after subsampling).
inline constexpr std::size_t kMaxVoteScenePoints = 65536;

// Device routine: features, votes and peaks for a subsampled scene cloud with normals (scaled to
// unit length here). Peaks are ordered by reference point, then rank (most votes first).
// Appends the stages "features", "vote", "peaks" to timings if given; the features are copied
// to *pairs if given (for tests). InputError for bad input or options.
std::vector<VotePeak> vote_peaks(ocl::Device& dev, const DeviceModel& model,
                                 const PointCloud& scene, const std::vector<std::uint32_t>& refs,
                                 const VoteOptions& opt = {}, StageTimings* timings = nullptr,
                                 ScenePairs* pairs = nullptr);

// References. The features with Eigen (ppf_pair_feature_reference): equal to the device's except
// where a value lies within rounding of a bin edge.
ScenePairs scene_pair_features_reference(const PointCloud& scene,
                                         const std::vector<std::uint32_t>& refs,
                                         const bp_ppf_quant& quant);
// inv_step = n_alpha / (2 pi) as a float, the value the kernel gets.
float ppf_vote_inv_step(const bp_ppf_quant& quant);
// A table's entries as the vote kernel reads them: (m_r n_alpha, bp_vote_offset(alpha_m)).
std::vector<bp_vote_entry> vote_entries(std::span<const bp_ppf_entry> entries,
                                        const bp_ppf_quant& quant);
// The alpha bin of alpha_s - alpha_m wrapped into [-pi, pi) (bins of 2 pi / n_alpha from -pi):
// the same float operations as the kernel (bp_vote_bin on bp_vote_offset), so given the same
// features the votes are identical. *frac, if given: the part of the bin past its start.
std::uint32_t ppf_vote_alpha_bin(float alpha_s, float alpha_m, const bp_ppf_quant& quant,
                                 float* frac = nullptr);
// The neighbouring bin a spread vote also goes to: the kernel's float operations.
std::uint32_t ppf_vote_alpha_neighbour(float alpha_s, float alpha_m, const bp_ppf_quant& quant);
// The accumulator (model points x alpha bins) of row r of pairs.
std::vector<std::uint32_t> vote_accumulator_reference(const ScenePairs& pairs, std::size_t r,
                                                      const PpfModel& model,
                                                      bool unique_votes = false,
                                                      bool spread_alpha = false);
// Whether cell c of an accumulator is a local maximum along alpha (ties count), as the kernel.
bool is_alpha_local_max(std::span<const std::uint32_t> acc, std::uint32_t c,
                        std::uint32_t n_alpha);
// Votes and peaks of given features, plain C++: with the device's features it must equal
// vote_peaks exactly.
std::vector<VotePeak> vote_peaks_reference(const ScenePairs& pairs, const PpfModel& model,
                                           const VoteOptions& opt = {});

}  // namespace binpick
