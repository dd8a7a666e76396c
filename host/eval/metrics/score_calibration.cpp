#include "host/eval/metrics/score_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include <fmt/format.h>

#include "host/core/atomic_file.hpp"
#include "host/eval/metrics/evaluate.hpp"

namespace binpick::eval {
namespace {

bool in_unit(double score) { return score >= 0 && score <= 1; }  // false for NaN

// Scores sorted highest first. A NaN score counts as -inf: below every threshold, so no threshold
// accepts it, and the sort stays a strict weak order.
std::vector<double> descending(std::vector<double> scores) {
  for (double& s : scores)
    if (std::isnan(s)) s = -std::numeric_limits<double>::infinity();
  std::sort(scores.begin(), scores.end(), std::greater<>());
  return scores;
}

// How many of the descending scores are >= t.
std::size_t at_least(const std::vector<double>& descending_scores, double t) {
  return std::size_t(std::upper_bound(descending_scores.begin(), descending_scores.end(), t,
                                      std::greater<>()) -
                     descending_scores.begin());
}

}  // namespace

std::size_t scores_outside_unit(const std::vector<HypothesisResult>& results) {
  return std::size_t(std::count_if(results.begin(), results.end(),
                                   [](const HypothesisResult& r) { return !in_unit(r.score); }));
}

ScoreCurve score_curve(const std::vector<HypothesisResult>& results, const OperatingPoint& at) {
  std::vector<double> all, right;
  for (const auto& r : results) {
    all.push_back(r.score);
    if (correct_at(r, at)) right.push_back(r.score);
  }
  ScoreCurve c;
  c.hypotheses = results.size();
  c.right = right.size();
  c.outside_unit = scores_outside_unit(results);
  all = descending(std::move(all));
  right = descending(std::move(right));
  for (int i = 0; i <= kScoreSteps; ++i) {
    // i / steps rather than a running sum, so 0.29 is the double nearest 0.29 and a score of
    // exactly 0.29 is accepted at it.
    const double t = double(i) / kScoreSteps;
    const std::size_t accepted = at_least(all, t), kept = at_least(right, t);
    c.threshold.push_back(t);
    c.accepted.push_back(accepted);
    c.precision.push_back(accepted ? double(kept) / double(accepted) : 1.0);
    c.kept.push_back(c.right ? double(kept) / double(c.right) : 0.0);
  }
  return c;
}

ScoreCalibration calibrate(const std::vector<HypothesisResult>& results, const OperatingPoint& at,
                           double keep) {
  ScoreCalibration c;
  c.keep = keep;
  c.hypotheses = results.size();
  c.outside_unit = scores_outside_unit(results);
  std::vector<double> all, right;
  for (const auto& r : results) {
    all.push_back(r.score);
    if (correct_at(r, at)) right.push_back(r.score);
  }
  all = descending(std::move(all));
  if (!all.empty()) c.max_score = all.front();
  right = descending(std::move(right));
  c.right = right.size();
  c.any_right = c.right > 0;
  if (!c.any_right) return c;
  // ceil(keep * R) less a hair, so that 0.9 * 70 = 63.000000000000007 asks for 63, not 64.
  const double wanted = keep > 0 ? std::ceil(keep * double(c.right) - 1e-9) : 1.0;
  const std::size_t n = std::size_t(std::clamp(wanted, 1.0, double(c.right)));
  c.threshold = right[n - 1];
  c.accepted = at_least(all, c.threshold);
  c.accepted_right = at_least(right, c.threshold);
  c.accepted_wrong = c.accepted - c.accepted_right;
  c.kept = double(c.accepted_right) / double(c.right);
  c.wrong_fraction = double(c.accepted_wrong) / double(c.accepted);
  return c;
}

std::string score_range_warning(const std::string& label, const ScoreCalibration& c) {
  if (!c.outside_unit) return "";
  return fmt::format(
      "{}: {} of {} scores are outside [0, 1] (highest {:g}): these results do not hold the "
      "verified score (vote counts from an older detect?), so the score calibration is about "
      "that column and its curve is not plotted",
      label, c.outside_unit, c.hypotheses, c.max_score);
}

std::string threshold_text(double threshold) {
  return in_unit(threshold) ? fmt::format("{:.3g}", threshold) : fmt::format("{:g}", threshold);
}

std::string calibration_line(const ScoreCalibration& c, const OperatingPoint& at) {
  if (!c.hypotheses) return "score: no hypotheses to calibrate it on";
  if (!c.any_right)
    return fmt::format("score: none of the {} hypotheses is right at ({:g} %, {:g} deg), so no "
                       "threshold to calibrate",
                       c.hypotheses, at.translation_pct, at.rotation_deg);
  return fmt::format(
      "score: threshold {} keeps {:g} % of right poses ({} of {}); {:.1f} % of the poses it "
      "accepts are wrong ({} of {}){}",
      threshold_text(c.threshold), 100 * c.keep, c.accepted_right, c.right, 100 * c.wrong_fraction,
      c.accepted_wrong, c.accepted, c.outside_unit ? " [scores not in [0, 1]]" : "");
}

void write_score_curves_csv(const std::filesystem::path& path,
                            const std::vector<LabelledScoreCurve>& all) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "label,threshold,accepted,precision,kept\n";
    for (const auto& lc : all) {
      // Labels are ours or directory names: quote them so a comma cannot shift the columns.
      std::string quoted = "\"";
      for (char ch : lc.label) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
      quoted += '"';
      const auto& c = lc.curve;
      for (std::size_t i = 0; i < c.threshold.size(); ++i)
        out << fmt::format("{},{:g},{},{:.6g},{:.6g}\n", quoted, c.threshold[i], c.accepted[i],
                           c.precision[i], c.kept[i]);
    }
  });
}

}  // namespace binpick::eval
