#include "host/shards/slurm_run.hpp"

#include <algorithm>
#include <chrono>
#include <ostream>
#include <thread>

#include <fmt/format.h>

#include "host/core/atomic_file.hpp"
#include "host/core/error.hpp"
#include "host/core/progress.hpp"
#include "host/core/read_file.hpp"
#include "host/shards/command_output.hpp"

namespace binpick {
namespace fs = std::filesystem;
namespace {

std::string trimmed(const std::string& text) {
  const std::size_t a = text.find_first_not_of(" \t\r\n");
  const std::size_t b = text.find_last_not_of(" \t\r\n");
  return a == std::string::npos ? "" : text.substr(a, b - a + 1);
}

std::string last_line(const fs::path& log) {
  if (!fs::is_regular_file(log)) return "no log";
  const std::string text = trimmed(read_file_bytes(log));
  const std::size_t nl = text.find_last_of('\n');
  return text.empty() ? "empty log" : nl == std::string::npos ? text : text.substr(nl + 1);
}

fs::path task_log(const fs::path& dir, int shard) {
  return dir / fmt::format("task_{}.log", shard);
}

std::string shard_names(const std::vector<int>& shards, int count) {
  std::string text;
  for (int s : shards) text += fmt::format("{}{}/{}", text.empty() ? "" : ", ", s + 1, count);
  return text;
}

// The array's tasks still queued or running: one state per line; none once the job is over
// (squeue fails for a job it no longer knows).
std::size_t tasks_in_queue(const std::string& job_id) {
  const CommandOutput q = capture_command({"squeue", "-h", "-r", "-j", job_id, "-o", "%T"});
  if (q.status != 0) return 0;
  std::size_t n = 0;
  for (char c : trimmed(q.text)) n += c == '\n';
  return trimmed(q.text).empty() ? 0 : n + 1;
}

// Waits for the array to leave the queue, drawing the shards done (their work all there).
void follow(const std::string& job_id, const ShardedBatch& batch, const std::vector<int>& shards) {
  Progress progress(fmt::format("slurm job {}", job_id), shards.size());
  const auto shards_done = [&] {
    const MissingWork m = missing_work(batch.record, batch.done);
    std::size_t done = 0;
    for (int s : shards) done += !std::binary_search(m.shards.begin(), m.shards.end(), s);
    return done;
  };
  for (;;) {
    const std::size_t queued = tasks_in_queue(job_id);
    progress.update(shards_done(), fmt::format("{} tasks queued or running", queued));
    if (queued == 0) break;
    std::this_thread::sleep_for(std::chrono::seconds(1));
  }
  progress.finish(fmt::format("{} of {} shards done", shards_done(), shards.size()));
}

// After the array: the merge, or which shards ended without their work.
void finish(const ShardedBatch& batch, const fs::path& dir, std::ostream& out) {
  const MissingWork after = missing_work(batch.record, batch.done);
  if (!after.shards.empty())
    throw InputError(fmt::format(
        "shards {} ended without their work ({}: {}); run the same command again to resubmit "
        "only them",
        shard_names(after.shards, batch.record.shards), task_log(dir, after.shards.front()).string(),
        last_line(task_log(dir, after.shards.front()))));
  out << batch.merge() << "\n";
}

}  // namespace

void run_on_slurm(const ShardedBatch& batch, const SlurmOptions& o,
                  const std::vector<std::string>& command, std::ostream& out) {
  const int count = batch.record.shards;
  const fs::path dir = batch.state_dir / "slurm";
  const MissingWork before = missing_work(batch.record, batch.done);
  std::vector<int> shards = before.shards;
  if (shards.empty() && o.dry_run)
    for (int s = 0; s < count; ++s) shards.push_back(s);
  if (shards.empty()) {
    out << "every shard is done\n" << batch.merge() << "\n";
    return;
  }
  // An earlier submission still queued or running (its follower was interrupted): follow it
  // rather than run its shards twice.
  const fs::path job_file = dir / "job_id";
  if (!o.dry_run && fs::is_regular_file(job_file) && on_path("squeue")) {
    const std::string earlier = trimmed(read_file_bytes(job_file));
    if (!earlier.empty() && tasks_in_queue(earlier) > 0) {
      out << fmt::format("job {} of an earlier submission is still in the queue: following it\n",
                         earlier) << std::flush;
      follow(earlier, batch, shards);
      return finish(batch, dir, out);
    }
  }
  const SlurmJob job{batch.record.verb, command, shards, dir, fs::current_path()};
  const std::string script = sbatch_script(job, o);
  if (o.dry_run) {
    out << script;
    return;
  }
  if (!on_path("sbatch") || !on_path("squeue"))
    throw InputError("--slurm: sbatch and squeue are not on PATH: run on a Slurm login node, or "
                     "without --slurm");
  fs::create_directories(dir);
  const fs::path script_path = dir / "array.sh";
  write_file_atomically(script_path, [&](std::ostream& s) { s << script; });
  std::error_code ec;
  for (int s : shards) fs::remove(task_log(dir, s), ec);  // a failure shows this run's log

  out << fmt::format("submitting shards {} as a Slurm job array ({})\n", shard_names(shards, count),
                     script_path.string())
      << std::flush;
  const CommandOutput submitted = capture_command({"sbatch", "--parsable", script_path.string()});
  const std::string reply = trimmed(submitted.text);
  const std::string job_id = reply.substr(0, reply.find_first_of(";\n"));
  if (submitted.status != 0 || job_id.empty() ||
      job_id.find_first_not_of("0123456789") != std::string::npos)
    throw InputError(fmt::format("sbatch {} failed: {}", script_path.string(), reply));
  write_file_atomically(job_file, [&](std::ostream& s) { s << job_id << "\n"; });
  out << fmt::format("job {}; task logs {}\n", job_id, (dir / "task_I.log").string()) << std::flush;
  follow(job_id, batch, shards);
  finish(batch, dir, out);
}

}  // namespace binpick
