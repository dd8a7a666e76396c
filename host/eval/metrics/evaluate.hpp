// Evaluation of detection results against a dataset's ground truth (paper section III-D): each
// hypothesis is matched to the ground-truth part nearest in translation, its errors are
// measured, and precision is counted for all hypotheses and for the top-ranked one (highest
// score) of each image, and per obj_id (per_object) of each image's rows of it; the score is calibrated against right and wrong (score_calibration.hpp).
// The numbers `binpick tune` optimises come from here.
#pragma once

#include <cstddef>
#include <vector>

#include "host/formats/bop/results_csv.hpp"
#include "host/eval/metrics/eval_dataset.hpp"
#include "host/eval/metrics/score_calibration.hpp"

namespace binpick::eval {

// A hypothesis is correct at an operating point when both errors are within its thresholds.
struct OperatingPoint {
  double translation_pct = 10;  // % of the diameter
  double rotation_deg = 15;
};

struct EvalOptions {
  OperatingPoint loose{10, 15};
  OperatingPoint strict{5, 5};
  double score_keep = 0.9;  // the score calibration's threshold keeps this fraction of right rows
  bool vsd = true;          // BOP's VSD too (renders the model at every estimate and target)
  double vsd_delta_mm = 15;  // its visibility tolerance (the toolkit's per-dataset vsd_deltas)
};

// Where a hypothesis' pose lies (landing()): on a part of the sought obj_id (right or wrong), on
// a part of another obj_id (a distractor), or on no part at all (the bin, the floor).
enum class Landing { part, distractor, none };

struct HypothesisResult {
  int scene_id = 0, im_id = 0, obj_id = 1;
  int rank = 0;          // 0 = the first row of its image in the file
  double score = 0;      // as detect writes it: the verified score in [0, 1]
  bool top = false;      // the highest score of its image (the first such row on ties)
  int gt_index = -1;     // the matched instance of scene_gt.json, -1 if the image has none of obj_id
  double translation_mm = 0, translation_pct = 0, rotation_deg = 0;  // +inf if unmatched
  double ms = 0;         // the image's time divided by its number of hypotheses
  Landing landing = Landing::part;
  bop::ResultRow row;    // as read
};

struct PrecisionAt {
  OperatingPoint at;
  double all = 0, top = 0;  // fraction of hypotheses / of top-ranked ones correct at `at`
};

struct EvalSummary {
  std::size_t images = 0;               // images of the dataset
  std::size_t images_with_results = 0;  // of them, images with at least one hypothesis
  std::size_t hypotheses = 0;
  std::size_t unmatched = 0;            // hypotheses of an obj_id absent from their image
  // Fractions of all hypotheses, and of the top-ranked one of each image, that landed on a
  // distractor or on no part (landing()).
  double all_on_distractor = 0, all_on_nothing = 0, top_on_distractor = 0, top_on_nothing = 0;
  PrecisionAt loose, strict;
  double median_translation_pct_all = 0, median_rotation_deg_all = 0;
  double median_translation_pct_top = 0, median_rotation_deg_top = 0;
  double ms_per_hypothesis = 0;
  // calibrate(results, loose / strict, score_keep): the score threshold keeping that fraction of
  // the right rows and the fraction of wrong ones it accepts.
  ScoreCalibration score_loose, score_strict;
  std::vector<HypothesisResult> results;  // in file order
};

// Throws InputError for a negative or non-finite threshold, or score_keep outside (0, 1].
void check(const EvalOptions& options);

// Throws InputError for a row of a scene or image the dataset does not have, or of an obj_id
// its models_info.json lacks, naming the row (1-based data row number, as in the file).
EvalSummary evaluate(const Dataset& dataset, const std::vector<bop::ResultRow>& rows,
                     const EvalOptions& options = {});

// The paper's figures of one obj_id's rows, their ranks and top-ranked row per image among that
// obj_id's rows alone: images are those whose ground truth holds the obj_id; results are left
// empty.
struct ObjectSummary {
  int obj_id = 0;
  EvalSummary summary;
};

// One summary per obj_id of all.results, ascending; empty when they hold fewer than two.
std::vector<ObjectSummary> per_object(const Dataset& dataset, const EvalSummary& all,
                                      const EvalOptions& options = {});

// Where the pose (R, t) of a part of obj_id lands in an image: the instance (any obj_id) whose
// bounding-box centre lies nearest the pose's, if within half that instance's diameter; a part
// of another obj_id is a distractor; no such instance means the pose lies on the bin or the floor.
Landing landing(const EvalImage& image, const bop::ModelsInfo& models, int obj_id,
                const Eigen::Matrix3d& R, const Eigen::Vector3d& t);

// Errors exactly at a threshold count as within it, whatever the last bit of their arithmetic
// (5.2 mm of a 52 mm part is 10 % of it).
inline constexpr double kThresholdSlack = 1e-9;

// True if r is within both thresholds of at (plus kThresholdSlack).
bool correct_at(const HypothesisResult& r, const OperatingPoint& at);

}  // namespace binpick::eval
