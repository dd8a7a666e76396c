#include "host/tune/tune_run.hpp"

#include <memory>
#include <ostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/formats/bop/png_image.hpp"
#include "host/formats/bop/results_csv.hpp"
#include "host/core/error.hpp"
#include "host/core/progress.hpp"
#include "host/detect/detect_params_file.hpp"
#include "host/eval/metrics/eval_dataset.hpp"
#include "host/eval/metrics/evaluate.hpp"
#include "host/core/atomic_file.hpp"
#include "host/core/read_file.hpp"
#include "host/detect/detect_step.hpp"
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

PpfTrainParams train_params(const TuneOptions& o, const TunePoint& p) {
  PpfTrainParams t;
  t.voxel_ratio = o.voxel_ratio;
  t.distance_steps = p.distance_steps;
  t.angle_steps = p.angle_steps;
  return t;
}

fs::path model_path(const TuneOptions& o, const TunePoint& p) {
  return o.out / "models" / fmt::format("d{}_a{}.ppfm", p.distance_steps, p.angle_steps);
}

// Measures points: the model of the point's steps (one loaded at a time, each trained once),
// detection of the dataset into the point's own results file, evaluation against the dataset.
class Measurer {
 public:
  Measurer(const TuneOptions& o, const Mesh& mesh, std::string part, eval::Dataset dataset)
      : o_(o), mesh_(mesh), part_(std::move(part)), dataset_(std::move(dataset)) {}

  TuneScore operator()(const TunePoint& p) {
    const TrainedModel& model = model_for(p);
    Detector detector(model.model, p.detect);
    const fs::path csv = o_.out / "evals" / (checksum_hex(point_key(p)) + ".csv");
    if (!warm_ && !fs::exists(csv)) warm_up(detector);
    detect_to_csv(detector, model, dataset_.root, csv);
    const eval::EvalSummary s = eval::evaluate(dataset_, bop::read_results_csv(csv));
    return {s.loose.top, s.loose.all, s.strict.top, s.strict.all, s.ms_per_hypothesis};
  }

  const TrainedModel& model_for(const TunePoint& p) {
    const fs::path path = model_path(o_, p);
    if (!model_ || model_->path != path)
      model_ = std::make_unique<TrainedModel>(
          train_or_reuse(mesh_, part_, train_params(o_, p), path));
    return *model_;
  }

 private:
  // The first detection of a process also builds the device programs: one image detected and
  // thrown away first, so that the first point measured is not charged for it.
  void warm_up(Detector& detector) {
    warm_ = true;
    const auto& [key, image] = *dataset_.images.begin();
    const auto png = read_png16(image.files.depth(key.im_id));
    detector.detect(DepthImage{png.width, png.height, png.pixels},
                    image_camera(image.camera.K, image.camera.depth_scale, png.width, png.height));
  }

  const TuneOptions& o_;
  const Mesh& mesh_;
  std::string part_;
  eval::Dataset dataset_;
  std::unique_ptr<TrainedModel> model_;
  bool warm_ = false;
};

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
  check_train_params(train_params(o, o.start));
  binpick::check(o.start.detect);
}

TuneResult run_tune(const Model& part, const TuneOptions& o, std::ostream& out) {
  check(o);
  const std::string description = describe(o.part);
  const SynthSummary made = synthesize(part, description, synth_options(o));
  out << fmt::format("dataset {}: {} bins ({} made now), {} parts each, noise {}\n",
                     (o.out / "dataset").string(), made.bins_made + made.bins_skipped,
                     made.bins_made, o.objects, o.noise);
  out << fmt::format("objective: top-voted precision at (10 %, 15 deg), then at (5 %, 5 deg), then "
                     "all hypotheses' precision, then time; at most {} ms per hypothesis\n\n",
                     o.search.budget_ms)
      << tune_table_header() << std::flush;

  Measurer measure(o, part.mesh, description, eval::load_dataset(o.out / "dataset"));
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
