// `--slurm`: runs a sharded batch as a Slurm job array from the submitting process. It writes the
// sbatch script into the batch's state directory, submits the shards that are not finished,
// follows the array with squeue (a progress bar over the shards), then merges. A rerun of the
// same command resubmits only the shards whose work is missing; with none missing it merges.
// If the array it submitted last (STATE/slurm/job_id) is still queued or running, because its
// follower was interrupted, a rerun follows that one instead of submitting its shards twice.
#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "host/shards/shard_record.hpp"
#include "host/shards/slurm_script.hpp"

namespace binpick {

struct ShardedBatch {
  std::filesystem::path state_dir;            // STATE/slurm/: the script and the task logs
  ShardRecord record;                         // the batch; record.shards = --tasks
  std::function<bool(int item)> done;         // whether an item's output is there
  std::function<std::string()> merge;         // the merged output; returns what to print
};

// With options.dry_run: prints the script of the shards to run and submits nothing. InputError
// when sbatch is missing or refuses, and when shards end without their work (naming them and
// their logs: the same command again resubmits them).
void run_on_slurm(const ShardedBatch& batch, const SlurmOptions& options,
                  const std::vector<std::string>& command, std::ostream& out);

}  // namespace binpick
