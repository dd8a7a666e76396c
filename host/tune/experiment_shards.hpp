// `run --shard K/N` and `run --slurm`: the experiment's work split by bin. Shard K makes bins
// K-1, K-1+N, ... of every noise level and detects those scenes (the bins it just made, so no
// shard waits for another); OUT/shards/shards.json records the batch. A bin is done when its
// detections are there at every level. The report needs every result, so it is made by the
// shard that finds all of them done, or by the same command again without --shard.
#pragma once

#include <filesystem>

#include "host/shards/shard_record.hpp"
#include "host/tune/experiment.hpp"

namespace binpick {

std::filesystem::path experiment_state_dir(const ExperimentOptions& o);  // OUT/shards

// Bins 0 .. bins-1 of the experiment in `shards` shards.
ShardRecord experiment_shard_record(const ExperimentOptions& o, int shards);

// Whether bin `bin` is detected at every noise level.
bool experiment_bin_done(const ExperimentOptions& o, int bin);

// Claims OUT/shards/shards.json for o.shard's batch (InputError while another is unfinished).
void claim_experiment_shards(const ExperimentOptions& o);

}  // namespace binpick
