#include "host/tune/tune_slurm.hpp"

#include <optional>
#include <ostream>

#include <fmt/format.h>

#include "host/core/output_lock.hpp"
#include "host/shards/slurm_run.hpp"
#include "host/tune/tune_candidates.hpp"
#include "host/tune/tune_measure.hpp"
#include "host/tune/tune_replay.hpp"

namespace binpick {
namespace fs = std::filesystem;
namespace {

fs::path tune_state_dir(const TuneOptions& o) { return o.out / "shards"; }

// One array: the batch's candidates as items 0..M-1, each done when its results are there.
ShardedBatch candidates_batch(const TuneOptions& o, const fs::path& file,
                              const std::vector<TunePoint>& points, int tasks) {
  ShardRecord record{"tune", fs::absolute(o.out), {}, tasks};
  for (std::size_t i = 0; i < points.size(); ++i) record.items.push_back(int(i));
  return {tune_state_dir(o) / file.stem(), record,
          [&o, points](int i) { return fs::exists(tune_results_csv(o, points[std::size_t(i)])); },
          [n = points.size()] { return fmt::format("{} points measured", n); }};
}

}  // namespace

void measure_candidates(const Model& part, const TuneOptions& o, const fs::path& file,
                        const Shard& shard, std::ostream& out) {
  check(o);
  const std::vector<TunePoint> points = read_candidates(file, o.start);
  TuneMeasurer measure(o, part.mesh, describe(o.part), eval::load_dataset(o.out / "dataset"));
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!shard.owns(i)) continue;
    const TuneScore s = measure(points[i]);
    out << fmt::format("point {} of {}: top {:.1f}%, {:.2f} ms per hypothesis ({})\n", i + 1,
                       points.size(), 100 * s.top, s.ms_per_hypothesis,
                       tune_results_csv(o, points[i]).string())
        << std::flush;
  }
}

void run_tune_on_slurm(const Model& part, const TuneOptions& o, const SlurmOptions& slurm,
                       const std::vector<std::string>& command, std::ostream& out) {
  check(o);
  if (!slurm.dry_run) {
    const OutputLock lock = OutputLock::directory(o.out);
    make_tune_dataset(part, o, out);
  }
  // Loaded once a measured point is looked up: a dry run before the dataset exists needs none.
  std::optional<TuneMeasurer> measurer;
  const auto measured = [&](const TunePoint& p) -> std::optional<TuneScore> {
    if (!fs::exists(tune_results_csv(o, p))) return std::nullopt;
    if (!measurer) measurer.emplace(o, part.mesh, describe(o.part), eval::load_dataset(o.out / "dataset"));
    return measurer->measured(p);
  };
  for (;;) {
    const SearchReplay replay = replay_search(o.start, o.search, measured);
    if (replay.result) break;
    fs::create_directories(tune_state_dir(o));
    const fs::path file = write_candidates(tune_state_dir(o), replay.next);
    std::vector<std::string> task = command;
    task.insert(task.end(), {"--points", fs::absolute(file).string()});
    out << fmt::format("{} points to measure ({})\n", replay.next.size(), file.string());
    run_on_slurm(candidates_batch(o, file, replay.next, slurm.tasks), slurm, task, out);
    if (slurm.dry_run) return;
  }
  const OutputLock lock = OutputLock::directory(o.out);
  if (!measurer) measurer.emplace(o, part.mesh, describe(o.part), eval::load_dataset(o.out / "dataset"));
  search_and_report(o, *measurer, out);
}

}  // namespace binpick
