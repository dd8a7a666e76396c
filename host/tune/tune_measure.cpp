#include "host/tune/tune_measure.hpp"

#include <fmt/format.h>

#include "host/detect/batch/detect_step.hpp"
#include "host/eval/metrics/evaluate.hpp"
#include "host/formats/bop/png_image.hpp"
#include "host/formats/bop/results_csv.hpp"
#include "host/tune/tune_run.hpp"

namespace binpick {
namespace fs = std::filesystem;

PpfTrainParams tune_train_params(const TuneOptions& o, const TunePoint& p) {
  PpfTrainParams t;
  t.voxel_ratio = o.voxel_ratio;
  t.distance_steps = p.distance_steps;
  t.angle_steps = p.angle_steps;
  return t;
}

fs::path tune_model_path(const TuneOptions& o, const TunePoint& p) {
  return o.out / "models" / fmt::format("d{}_a{}.ppfm", p.distance_steps, p.angle_steps);
}

fs::path tune_results_csv(const TuneOptions& o, const TunePoint& p) {
  return o.out / "evals" / (checksum_hex(point_key(p)) + ".csv");
}

TuneMeasurer::TuneMeasurer(const TuneOptions& o, const Mesh& mesh, std::string part,
                           eval::Dataset dataset)
    : o_(o), mesh_(mesh), part_(std::move(part)), dataset_(std::move(dataset)) {}

TuneScore TuneMeasurer::operator()(const TunePoint& p) {
  const TrainedModel& model = model_for(p);
  Detector detector(model.model, p.detect);
  const fs::path csv = tune_results_csv(o_, p);
  if (!warm_ && !fs::exists(csv)) warm_up(detector);
  detect_to_csv(detector, model, dataset_.root, csv);
  return evaluate(csv);
}

std::optional<TuneScore> TuneMeasurer::measured(const TunePoint& p) const {
  const fs::path csv = tune_results_csv(o_, p);
  if (!fs::exists(csv)) return std::nullopt;
  return evaluate(csv);
}

TuneScore TuneMeasurer::evaluate(const fs::path& csv) const {
  const eval::EvalSummary s = eval::evaluate(dataset_, bop::read_results_csv(csv));
  return {s.loose.top, s.loose.all, s.strict.top, s.strict.all, s.ms_per_hypothesis};
}

const TrainedModel& TuneMeasurer::model_for(const TunePoint& p) {
  const fs::path path = tune_model_path(o_, p);
  if (!model_ || model_->path != path)
    model_ = std::make_unique<TrainedModel>(
        train_or_reuse(mesh_, part_, tune_train_params(o_, p), path));
  return *model_;
}

void TuneMeasurer::warm_up(Detector& detector) {
  warm_ = true;
  const auto& [key, image] = *dataset_.images.begin();
  const auto png = read_png16(image.files.depth(key.im_id));
  detector.detect(DepthView{png.width, png.height, png.pixels},
                  image_camera(image.camera.K, image.camera.depth_scale, png.width, png.height));
}

}  // namespace binpick
