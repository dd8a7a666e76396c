// `binpick tune --slurm`: the tuning search with its measurements done by Slurm job arrays.
// This process makes the dataset, then replays the search over the points measured so far
// (tune_replay.hpp); each batch of candidates it cannot do without becomes one job array whose
// task K measures its round-robin share of the batch (`tune --points FILE --shard K/N`, the
// same command otherwise). Once the search needs nothing more it prints the table and writes
// the files exactly as `tune` without --slurm does (every result is then only re-read). Every
// measurement stays in OUT/evals/, so a rerun resumes and resubmits only what is missing; an
// array still queued from an interrupted run is followed, not submitted twice
// (host/shards/slurm_run.hpp). The state of each array: OUT/shards/points-HASH/slurm/.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "host/shards/shard.hpp"
#include "host/shards/slurm_script.hpp"
#include "host/tune/tune_run.hpp"

namespace binpick {

// `tune --points FILE [--shard K/N]`: measures the points of FILE (with a shard: those at
// its positions) on OUT/dataset, which must be there; a line per point to `out`.
void measure_candidates(const Model& part, const TuneOptions& options,
                        const std::filesystem::path& file, const Shard& shard, std::ostream& out);

// `tune --slurm`. `command`: this process's command line without the sharding and Slurm
// options (task_command). Takes the output's lock itself, only while no array runs (the tasks
// hold it shared). With slurm.dry_run: prints the first array's script (its candidates file is
// written; the dataset is not made).
void run_tune_on_slurm(const Model& part, const TuneOptions& options, const SlurmOptions& slurm,
                       const std::vector<std::string>& command, std::ostream& out);

}  // namespace binpick
