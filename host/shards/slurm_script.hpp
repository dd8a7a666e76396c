// The sbatch script of a sharded batch (`--slurm`): a job array whose task I runs the same
// binpick command with --shard I+1/N. Only the shards given are in the array, so a rerun
// submits just the ones that did not finish.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace binpick {

struct SlurmOptions {
  bool enabled = false;       // --slurm
  bool dry_run = false;       // --dry-run: print the script, submit nothing
  int tasks = 4;              // --tasks: N, the number of shards
  std::string partition;      // --partition ("": the cluster's default)
  std::string time;           // --time limit per task ("": the partition's)
  int cpus_per_task = 0;      // --cpus-per-task (0: Slurm's default)
  std::string mem;            // --mem per task ("": the partition's)
};

struct SlurmJob {
  std::string verb;                     // job name binpick-VERB
  std::vector<std::string> command;     // binpick and its arguments, without --shard and --slurm's
  std::vector<int> shards;              // 0-based array indices to run
  std::filesystem::path log_dir;        // task logs: LOG_DIR/task_%a.log
  std::filesystem::path workdir;        // where the tasks run (relative paths in the command)
};

// "0-3", "1,3", "0,2-5": the array indices for sbatch --array.
std::string array_spec(const std::vector<int>& shards);

// The script's text. InputError for options sbatch could not take.
std::string sbatch_script(const SlurmJob& job, const SlurmOptions& options);

// binpick's argument list without the options that choose sharding and Slurm (--shard, --slurm,
// --dry-run, --tasks, --partition, --time, --cpus-per-task, --mem, also as --name=value): what
// every array task runs, followed by its own --shard.
std::vector<std::string> task_command(const std::vector<std::string>& argv);

// This process's command line (/proc/self/cmdline), the program as an absolute path
// (/proc/self/exe), so array tasks run the same binary.
std::vector<std::string> own_command_line();

}  // namespace binpick
