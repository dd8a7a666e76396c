// The options of the batch verbs that split their work (synth, detect): --shard K/N for one
// process's share, or --slurm to run all N shards as a Slurm job array (--tasks N, --partition,
// --time, --cpus-per-task, --mem; --dry-run prints the sbatch script). Declared here once so a
// verb adds them with one line.
#pragma once

#include <string>

#include "host/core/cli_fwd.hpp"

#include "host/shards/shard.hpp"
#include "host/shards/slurm_script.hpp"

namespace binpick::cli {

struct ShardCliOptions {
  std::string shard;   // "K/N" or ""
  SlurmOptions slurm;
};

// `items` names what is split ("scenes", "bins").
void add_shard_options(CLI::App* verb, ShardCliOptions& o, const std::string& items);

// --shard parsed (InputError for a bad K/N).
Shard shard_of(const ShardCliOptions& o);

// For a verb whose output cannot be split (eval): --shard that only says why, as one usage error.
void add_unsharded_option(CLI::App* verb, std::string& shard, const std::string& why);
void refuse_shard(const std::string& shard, const std::string& verb, const std::string& why);

}  // namespace binpick::cli
