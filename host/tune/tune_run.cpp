#include "host/tune/tune_run.hpp"

#include <ostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/core/error.hpp"
#include "host/core/progress.hpp"
#include "host/detect/params/params_file.hpp"
#include "host/eval/metrics/eval_dataset.hpp"
#include "host/core/atomic_file.hpp"
#include "host/core/read_file.hpp"
#include "host/tune/tune_measure.hpp"
#include "host/tune/tune_table.hpp"
#include "synth/synthesize.hpp"

namespace binpick {
namespace fs = std::filesystem;
namespace {

SynthOptions synth_options(const TuneOptions& o) {
  SynthOptions s;
  s.out = o.out / "dataset";
  s.bins = o.bins;
  s.seed = o.seed;
  s.noise = o.noise;
  s.width = o.width;
  s.height = o.height;
  s.drop.objects = o.objects;
  s.drop.max_wall_seconds = o.max_wall_seconds;
  return s;
}

void copy_atomically(const fs::path& from, const fs::path& to) {
  const std::string bytes = read_file_bytes(from);
  write_file_atomically(to, [&](std::ostream& s) { s << bytes; });
}

}  // namespace

void check(const TuneOptions& o) {
  if (o.out.empty()) throw InputError("--out: a working directory is required");
  if (fs::exists(o.out) && !fs::is_directory(o.out))
    throw InputError("--out " + o.out.string() + " exists and is not a directory");
  validate_synth_options(synth_options(o));
  check(o.search);
  check_train_params(tune_train_params(o, o.start));
  binpick::check(o.start.detect);
}

void make_tune_dataset(const Model& part, const TuneOptions& o, std::ostream& out) {
  check(o);
  const SynthSummary made = synthesize(part, describe(o.part), synth_options(o));
  out << fmt::format("dataset {}: {} bins ({} made now), {} parts each, noise {}\n",
                     (o.out / "dataset").string(), made.bins_made + made.bins_skipped,
                     made.bins_made, o.objects, o.noise) << std::flush;
}

TuneResult run_tune(const Model& part, const TuneOptions& o, std::ostream& out) {
  make_tune_dataset(part, o, out);
  TuneMeasurer measure(o, part.mesh, describe(o.part), eval::load_dataset(o.out / "dataset"));
  return search_and_report(o, measure, out);
}

TuneResult search_and_report(const TuneOptions& o, TuneMeasurer& measure, std::ostream& out) {
  out << fmt::format("objective: top-voted precision at (10 %, 15 deg), then at (5 %, 5 deg), then "
                     "all hypotheses' precision, then time; at most {} ms per hypothesis\n\n",
                     o.search.budget_ms)
      << tune_table_header() << std::flush;

  TuneResult r;
  r.table_csv = o.out / "tune.csv";
  Progress progress("tune", max_measurements(o.search));
  std::vector<TuneRow> rows;  // as they come, for tune.csv
  r.search = coordinate_descent(
      o.start, o.search, [&](const TunePoint& p) { return measure(p); },
      [&](const TuneRow& row, std::size_t best) {
        rows.push_back(row);
        write_tune_csv(r.table_csv, rows, best);
        out << tune_table_row(row, row.index == best) << std::flush;
        progress.update(rows.size(), fmt::format("best {:.1f}% top", 100 * rows[best].score.top));
      });
  progress.finish(fmt::format("{} points measured", r.search.rows.size()));

  const TuneRow& winner = r.search.rows[r.search.best];
  r.best = winner.point;
  write_tune_csv(r.table_csv, r.search.rows, r.search.best);
  r.best_json = o.out / "best.json";
  write_file_atomically(r.best_json, [&](std::ostream& s) {
    s << nlohmann::json::parse(params_json(r.best.detect)).dump(1) << "\n";
  });
  const TrainedModel& model = measure.model_for(r.best);
  r.best_model = o.out / "best.ppfm";
  copy_atomically(model.path, r.best_model);
  copy_atomically(fs::path(model.path.string() + ".json"), fs::path(r.best_model.string() + ".json"));
  r.best_train_json = o.out / "best-train.json";
  const nlohmann::json train = {{"voxel-ratio", o.voxel_ratio},
                                {"distance-steps", r.best.distance_steps},
                                {"angle-steps", r.best.angle_steps}};
  write_file_atomically(r.best_train_json, [&](std::ostream& s) { s << train.dump(1) << "\n"; });

  out << "\nbest (row " << winner.index << "):\n" << tune_table_header()
      << tune_table_row(winner, true);
  if (!winner.within_budget)
    out << fmt::format("warning: no point measured fits the budget of {} ms per hypothesis; "
                       "this is the fastest\n", o.search.budget_ms);
  out << fmt::format(
      "\nwrote {} (table), {} (detect --params), {} (its model)\n"
      "the parameters belong to a model trained with --distance-steps {} --angle-steps {} "
      "--voxel-ratio {}:\n  binpick detect --model {} --params {} --dataset ... --out ...\n",
      r.table_csv.string(), r.best_json.string(), r.best_model.string(), r.best.distance_steps,
      r.best.angle_steps, o.voxel_ratio, r.best_model.string(), r.best_json.string());
  return r;
}

}  // namespace binpick
