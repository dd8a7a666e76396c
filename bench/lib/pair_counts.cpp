#include "bench/lib/pair_counts.hpp"

#include "host/detect/vote/ppf_vote.hpp"

namespace binpick::bench {

PairCounts& PairCounts::operator+=(const PairCounts& o) {
  pairs += o.pairs;
  lookups += o.lookups;
  votes += o.votes;
  cells += o.cells;
  return *this;
}

PairCounts count_pairs(const PointCloud& subsampled, double ref_ratio, const PpfModel& model) {
  PairCounts c;
  if (subsampled.points.empty()) return c;
  const auto refs = select_reference_points(subsampled.points.size(), ref_ratio);
  const ScenePairs pairs = scene_pair_features_reference(subsampled, refs, model.quant);
  c.pairs = double(pairs.keys.size());
  for (std::uint32_t key : pairs.keys) {
    if (key == BP_PPF_NO_KEY) continue;
    c.lookups += 1;
    c.votes += double(model.table.offsets[key + 1] - model.table.offsets[key]);
  }
  c.cells = double(refs.size()) * double(model.cloud.points.size()) * model.quant.n_alpha;
  return c;
}

}  // namespace binpick::bench
