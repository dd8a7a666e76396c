// BOP's average recalls of detection results (eval_bop19_pose.py): MSSD at thresholds 0.05..0.5
// of the diameter, MSPD at 5..50 px scaled to a 640 px wide image, each matched and counted per
// threshold (bop_matching.hpp) and averaged into AR_MSSD and AR_MSPD. Of each image and obj_id
// only the inst_count best-scored estimates count (the toolkit's n_top = -1), against the
// targets of bop_targets.hpp. VSD (bop_vsd_recall.hpp) renders the model with Vulkan; with it
// AR is BOP's, the mean of AR_VSD, AR_MSSD and AR_MSPD; without it (not asked for, or no depth
// images) the mean of the other two stands in.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "host/eval/metrics/bop_matching.hpp"
#include "host/eval/metrics/bop_vsd_recall.hpp"
#include "host/eval/metrics/eval_dataset.hpp"
#include "host/formats/bop/results_csv.hpp"

namespace binpick::eval {

struct BopScores {
  // Why there are no scores (the dataset has no model file to measure on); empty if there are.
  std::string unavailable;
  std::string targets_source;            // bop_targets()
  std::filesystem::path vertices;        // models_eval/ or models/
  double image_width = 640;              // px; MSPD errors are scaled by 640 / image_width
  bool image_width_known = false;        // from camera.json; else 640 was assumed
  int targets = 0;                       // target instances
  int estimates = 0;                     // estimates considered (at most inst_count per group)
  MetricRecall mssd, mspd;
  bool has_vsd = false;                  // vsd holds BOP's VSD recalls
  VsdRecall vsd;                         // its `unavailable` says why not, if asked for
  double average_recall = 0;             // (AR_VSD + AR_MSSD + AR_MSPD) / 3, or of the two
};

struct BopOptions {
  bool vsd = true;  // render and compute VSD (the expensive one of the three)
  double vsd_delta_mm = kBopVsdDelta;
};

// Thresholds of eval_bop19_pose.py: MSSD arange(0.05, 0.51, 0.05) (fraction of the diameter),
// MSPD arange(5, 51, 5) (px at 640 px width).
std::vector<double> bop_mssd_thresholds();
std::vector<double> bop_mspd_thresholds();

// Rows of images or obj_ids without targets are ignored (BOP evaluates targets only). Without a
// model file of a target's obj_id the scores are `unavailable` (eval still gives the paper's
// figures, which need models_info.json only). Throws InputError for a model or targets file that
// cannot be read.
BopScores bop_scores(const Dataset& dataset, const std::vector<bop::ResultRow>& rows,
                     const BopOptions& options = {});

}  // namespace binpick::eval
