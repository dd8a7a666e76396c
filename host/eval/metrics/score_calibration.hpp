// Whether the detection score can be trusted as a confidence: precision of the poses a score
// threshold accepts, and the threshold that keeps a given fraction (90 %) of the right poses with
// the fraction of wrong poses it lets through. The requirement the report checks: at the
// threshold that keeps 90 % of right poses, at most 5 % of the accepted poses are wrong.
//
// Right and wrong are correct_at(r, at) over every row of the results (matched or not: a row of
// an obj_id absent from its image is wrong), not only the top-ranked one of each image, since a
// robot picks any pose whose score clears its threshold.
#pragma once

#include <cstddef>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace binpick::eval {

// Declared here rather than included: evaluate.hpp holds the calibration in its summary.
struct HypothesisResult;
struct OperatingPoint;

// The requirement: at the calibrated threshold at most this fraction of accepted poses is wrong.
inline constexpr double kScoreMaxWrong = 0.05;

// The score threshold axis: 0, 0.01, ..., 1, where the verified score lives.
inline constexpr int kScoreSteps = 100;

struct ScoreCurve {
  std::vector<double> threshold;          // 0, 1 / kScoreSteps, ..., 1
  std::vector<std::size_t> accepted;      // hypotheses with score >= threshold
  std::vector<double> precision;          // right accepted / accepted; 1 when none is accepted
                                          // (no accepted pose is wrong)
  std::vector<double> kept;               // right accepted / all right; 0 without a right one
  std::size_t hypotheses = 0, right = 0;  // over all rows
  std::size_t outside_unit = 0;           // scores outside [0, 1] (see scores_outside_unit)
};

// One curve over every row of results, right and wrong at `at`.
ScoreCurve score_curve(const std::vector<HypothesisResult>& results, const OperatingPoint& at);

inline constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

// With R right rows (R > 0) whose scores, highest first, are s_1 >= s_2 >= ... >= s_R, and
// n = ceil(keep * R) clamped to [1, R]: threshold = s_n. It is exact, not on a grid: the largest t
// such that the rows with score >= t include at least keep * R right ones (a higher t would lose
// s_n and everything tied with it, leaving fewer than n). accepted counts every row with
// score >= threshold, right or wrong, and wrong_fraction = accepted_wrong / accepted.
// Without a right row no threshold keeps any: any_right is false, threshold, kept and
// wrong_fraction are NaN (null in report.json) and the counts of accepted rows are 0.
struct ScoreCalibration {
  double keep = 0.9;                // the fraction of right rows to keep, in (0, 1]
  std::size_t hypotheses = 0;       // all rows
  std::size_t right = 0;            // rows right at the operating point
  bool any_right = false;
  double threshold = kNoValue;
  std::size_t accepted = 0, accepted_right = 0, accepted_wrong = 0;
  double kept = kNoValue;            // accepted_right / right, >= keep
  double wrong_fraction = kNoValue;  // accepted_wrong / accepted
  // Scores outside [0, 1] (or NaN): the results do not hold the verified score (an older file
  // with vote counts, say). The numbers above are still exact for whatever the column holds,
  // but the score axis of the curves does not fit them: the report warns instead of plotting.
  std::size_t outside_unit = 0;
  double max_score = kNoValue;       // the highest score, for that warning
};

ScoreCalibration calibrate(const std::vector<HypothesisResult>& results, const OperatingPoint& at,
                           double keep = 0.9);

// Rows whose score is not in [0, 1] (NaN included).
std::size_t scores_outside_unit(const std::vector<HypothesisResult>& results);

// A one-line warning for a dataset whose scores are outside [0, 1], or "" if they all fit.
std::string score_range_warning(const std::string& label, const ScoreCalibration& c);

// A threshold as the report prints it: 3 significant digits in [0, 1] ("0.62"), else as %g
// ("4211", not "4.21e+03").
std::string threshold_text(double threshold);

// The console's line, e.g. "score: threshold 0.62 keeps 90 % of right poses (376 of 417); 3.1 %
// of the poses it accepts are wrong (12 of 388)", or why there is no threshold.
std::string calibration_line(const ScoreCalibration& c, const OperatingPoint& at);

struct LabelledScoreCurve {
  std::string label;  // the dataset's
  ScoreCurve curve;
  ScoreCalibration calibration;  // at the curve's operating point; marked on the plot
};

// score_curves.csv: label,threshold,accepted,precision,kept (one line a point, long format).
void write_score_curves_csv(const std::filesystem::path& path,
                            const std::vector<LabelledScoreCurve>& all);

}  // namespace binpick::eval
