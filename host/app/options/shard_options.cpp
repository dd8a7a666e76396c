#include "host/app/options/shard_options.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "host/core/error.hpp"

namespace binpick::cli {

void add_shard_options(CLI::App* verb, ShardCliOptions& o, const std::string& items) {
  auto* shard = verb->add_option(
      "--shard", o.shard,
      fmt::format("K/N: do only the K-th of N deterministic shares of the {} (round robin in "
                  "order) and write its partial output; the shard that finishes last merges "
                  "(or `binpick merge`); the merged output is the unsharded run's",
                  items));
  auto* slurm = verb->add_flag(
      "--slurm", o.slurm.enabled,
      "run as a Slurm job array of --tasks shards: write the sbatch script into the output's "
      "state directory, submit it, follow the tasks, merge; run again to resubmit only the "
      "shards that did not finish");
  slurm->excludes(shard);
  verb->add_option("--tasks", o.slurm.tasks, "with --slurm: the number of shards (array tasks)")
      ->capture_default_str()
      ->needs(slurm);
  verb->add_option("--partition", o.slurm.partition, "with --slurm: the Slurm partition")->needs(slurm);
  verb->add_option("--time", o.slurm.time, "with --slurm: time limit per task (Slurm's format, e.g. 30:00)")
      ->needs(slurm);
  verb->add_option("--cpus-per-task", o.slurm.cpus_per_task, "with --slurm: CPUs per task")->needs(slurm);
  verb->add_option("--mem", o.slurm.mem, "with --slurm: memory per task (e.g. 4G)")->needs(slurm);
  verb->add_flag("--dry-run", o.slurm.dry_run,
                 "with --slurm: print the sbatch script of the shards still to do; submit nothing")
      ->needs(slurm);
}

Shard shard_of(const ShardCliOptions& o) {
  if (o.slurm.enabled && (o.slurm.tasks < 1 || o.slurm.tasks > 100000))
    throw InputError("--tasks must be between 1 and 100000");
  return parse_shard(o.shard);
}

void add_unsharded_option(CLI::App* verb, std::string& shard, const std::string& why) {
  verb->add_option("--shard", shard, "not taken: " + why);
}

void refuse_shard(const std::string& shard, const std::string& verb, const std::string& why) {
  if (!shard.empty()) throw InputError(fmt::format("{} takes no --shard: {}", verb, why));
}

}  // namespace binpick::cli
