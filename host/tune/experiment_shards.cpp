#include "host/tune/experiment_shards.hpp"

#include "host/detect/batch/detect_parts.hpp"

namespace binpick {
namespace fs = std::filesystem;

fs::path experiment_state_dir(const ExperimentOptions& o) { return o.out / "shards"; }

ShardRecord experiment_shard_record(const ExperimentOptions& o, int shards) {
  ShardRecord r{"run", fs::absolute(o.out), {}, shards};
  for (int b = 0; b < o.bins; ++b) r.items.push_back(b);
  return r;
}

bool experiment_bin_done(const ExperimentOptions& o, int bin) {
  for (double noise : o.noise)
    if (!scene_done(experiment_results_csv(o, noise), bin)) return false;
  return true;
}

void claim_experiment_shards(const ExperimentOptions& o) {
  fs::create_directories(experiment_state_dir(o));
  claim_shard_record(experiment_state_dir(o) / "shards.json",
                     experiment_shard_record(o, o.shard.count),
                     [&](int bin) { return experiment_bin_done(o, bin); });
}

}  // namespace binpick
