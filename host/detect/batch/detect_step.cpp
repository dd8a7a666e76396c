#include "host/detect/batch/detect_step.hpp"

#include "host/core/error.hpp"

namespace binpick {

BatchSummary detect_to_csv(Detector& detector, const TrainedModel& model,
                           const std::filesystem::path& dataset, const std::filesystem::path& csv,
                           const Shard& shard, const std::vector<int>& scenes) {
  if (&detector.model() != &model.model)
    throw std::logic_error("detect_to_csv: the detector was not made from this model");
  std::error_code ec;
  if (csv.has_parent_path()) std::filesystem::create_directories(csv.parent_path(), ec);
  if (ec) throw InputError("cannot create " + csv.parent_path().string() + ": " + ec.message());
  BatchOptions opt;
  opt.dataset = dataset;
  opt.out = csv;
  opt.model_checksum = model.checksum;
  opt.shard = shard;
  opt.scenes = scenes;
  return detect_dataset(detector, opt, nullptr);
}

}  // namespace binpick
