#include "host/shards/slurm_script.hpp"

#include <algorithm>
#include <array>
#include <string_view>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/core/read_file.hpp"
#include "host/core/shell_quote.hpp"

namespace binpick {
namespace fs = std::filesystem;
namespace {

constexpr std::array<std::string_view, 2> kFlags{"--slurm", "--dry-run"};
constexpr std::array<std::string_view, 6> kValued{"--shard",         "--tasks", "--partition",
                                                  "--time", "--cpus-per-task", "--mem"};

// Slurm reads #SBATCH lines itself: a value with a space or a quote would be cut there.
std::string sbatch_value(const std::string& option, const std::string& value) {
  if (value.find_first_of(" \t\n'\"#") != std::string::npos)
    throw InputError(fmt::format("{} '{}': no spaces, quotes or # in a Slurm option", option, value));
  return value;
}

}  // namespace

std::string array_spec(const std::vector<int>& shards) {
  std::vector<int> sorted = shards;
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  std::string spec;
  for (std::size_t i = 0; i < sorted.size();) {
    std::size_t j = i;
    while (j + 1 < sorted.size() && sorted[j + 1] == sorted[j] + 1) ++j;
    if (!spec.empty()) spec += ",";
    spec += j == i ? fmt::format("{}", sorted[i]) : fmt::format("{}-{}", sorted[i], sorted[j]);
    i = j + 1;
  }
  return spec;
}

std::string sbatch_script(const SlurmJob& job, const SlurmOptions& o) {
  if (job.shards.empty()) throw InputError("sbatch_script: no shard to run");
  if (o.tasks < 1 || o.tasks > 100000) throw InputError("--tasks must be between 1 and 100000");
  if (o.cpus_per_task < 0) throw InputError("--cpus-per-task must not be negative");
  std::string s = "#!/bin/sh\n";
  s += fmt::format("# binpick {}: {} shards as a Slurm job array; task I runs shard I+1/{}.\n",
                   job.verb, o.tasks, o.tasks);
  s += fmt::format("#SBATCH --job-name=binpick-{}\n", job.verb);
  s += fmt::format("#SBATCH --array={}\n", array_spec(job.shards));
  s += fmt::format("#SBATCH --output={}\n",
                   sbatch_value("--out", (fs::absolute(job.log_dir) / "task_%a.log").string()));
  s += fmt::format("#SBATCH --chdir={}\n", sbatch_value("the working directory",
                                                         fs::absolute(job.workdir).string()));
  if (!o.partition.empty()) s += "#SBATCH --partition=" + sbatch_value("--partition", o.partition) + "\n";
  if (!o.time.empty()) s += "#SBATCH --time=" + sbatch_value("--time", o.time) + "\n";
  if (o.cpus_per_task > 0) s += fmt::format("#SBATCH --cpus-per-task={}\n", o.cpus_per_task);
  if (!o.mem.empty()) s += "#SBATCH --mem=" + sbatch_value("--mem", o.mem) + "\n";
  s += "set -e\n";
  s += fmt::format("exec {} --shard \"$((SLURM_ARRAY_TASK_ID + 1))/{}\"\n",
                   shell_command(job.command), o.tasks);
  return s;
}

std::vector<std::string> task_command(const std::vector<std::string>& argv) {
  std::vector<std::string> kept;
  for (std::size_t i = 0; i < argv.size(); ++i) {
    const std::string_view a = argv[i];
    const std::string_view name = a.substr(0, a.find('='));
    if (std::find(kFlags.begin(), kFlags.end(), a) != kFlags.end()) continue;
    if (std::find(kValued.begin(), kValued.end(), name) != kValued.end()) {
      if (name == a) ++i;  // "--tasks 4": skip the value too
      continue;
    }
    kept.push_back(argv[i]);
  }
  return kept;
}

std::vector<std::string> own_command_line() {
  const std::string bytes = read_file_bytes("/proc/self/cmdline");
  std::vector<std::string> argv;
  for (std::size_t start = 0; start < bytes.size();) {
    const std::size_t end = bytes.find('\0', start);
    argv.push_back(bytes.substr(start, end == std::string::npos ? end : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!argv.empty() && !ec) argv[0] = exe.string();
  return argv;
}

}  // namespace binpick
