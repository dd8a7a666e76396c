// BOP's matching of estimates to ground truth and its recall (bop_toolkit_lib/pose_matching.py
// match_poses, score.py calc_localization_scores), for one pose error at a list of thresholds.
#pragma once

#include <utility>
#include <vector>

namespace binpick::eval {

// One estimate BOP considers: its errors to the target instances of its image and obj_id,
// already normalised (MSSD / diameter, MSPD * 640 / image width), by instance index ascending.
struct EstimateErrors {
  std::vector<std::pair<int, double>> errors;  // (instance index in the image, error)
};

// The estimates of one obj_id in one image, in the order BOP matches them (score descending,
// file order on ties, the first inst_count only), and how many target instances it has.
struct TargetGroup {
  int obj_id = 1;
  int targets = 0;
  std::vector<EstimateErrors> estimates;
};

// Greedy matching: each estimate in turn takes the not yet matched instance with the smallest
// error below the threshold (strictly; the first instance on ties). Returns how many instances
// were matched.
int matched_instances(const std::vector<EstimateErrors>& estimates, double threshold);

struct RecallCurve {
  std::vector<double> thresholds, recall;  // recall = matched targets / targets (0 without targets)
  double average = 0;                      // mean of recall over the thresholds (BOP's AR_X)
};

struct ObjectRecall {
  int obj_id = 1;
  int targets = 0;
  RecallCurve curve;
};

struct MetricRecall {
  RecallCurve overall;                // over all targets (what BOP reports)
  std::vector<ObjectRecall> objects;  // by obj_id ascending
};

MetricRecall recall_over_thresholds(const std::vector<TargetGroup>& groups,
                                    const std::vector<double>& thresholds);

// numpy's arange(start, stop, step): start + i * step for i < ceil((stop - start) / step), the
// very numbers BOP's scripts compare against.
std::vector<double> arange(double start, double stop, double step);

}  // namespace binpick::eval
