// How `binpick tune` measures a point: the model of the point's steps (trained once into
// OUT/models/dD_aA.ppfm, one loaded at a time), detection of the tuning dataset into the point's
// own results file OUT/evals/KEY.csv (resumable, so a measured point is only re-read), and its
// evaluation against the dataset.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "host/eval/metrics/eval_dataset.hpp"
#include "host/train/model_store.hpp"
#include "host/tune/tune_search.hpp"

namespace binpick {

struct TuneOptions;

// The training parameters of a point's model: the tune's voxel, the point's steps.
PpfTrainParams tune_train_params(const TuneOptions& o, const TunePoint& p);
// OUT/models/dD_aA.ppfm: the model of a point's steps.
std::filesystem::path tune_model_path(const TuneOptions& o, const TunePoint& p);
// OUT/evals/KEY.csv: a point's detection results; there once the point is measured.
std::filesystem::path tune_results_csv(const TuneOptions& o, const TunePoint& p);

class TuneMeasurer {
 public:
  // `mesh` and `part` (its description) are the part's; `dataset` is OUT/dataset, loaded.
  TuneMeasurer(const TuneOptions& o, const Mesh& mesh, std::string part, eval::Dataset dataset);

  // Detects (unless the point's results are there) and evaluates.
  TuneScore operator()(const TunePoint& p);
  // The score of a point measured before (its results there), nullopt if it is not.
  std::optional<TuneScore> measured(const TunePoint& p) const;
  // The model of the point's steps, trained now unless it is there.
  const TrainedModel& model_for(const TunePoint& p);

 private:
  // The first detection of a process also builds the device programs: one image detected and
  // thrown away first, so that the first point measured is not charged for it.
  void warm_up(class Detector& detector);
  TuneScore evaluate(const std::filesystem::path& csv) const;

  const TuneOptions& o_;
  const Mesh& mesh_;
  std::string part_;
  eval::Dataset dataset_;
  std::unique_ptr<TrainedModel> model_;
  bool warm_ = false;
};

}  // namespace binpick
