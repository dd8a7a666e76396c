// The score calibration of `binpick eval` on hand-made hypotheses whose answer is known: the
// threshold keeping 90 % of the right poses, the wrong fraction it lets through, the curves of
// precision and kept fraction against the threshold, and the cases without an answer (no right
// pose, no hypotheses, scores that are vote counts rather than the verified score).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "host/core/error.hpp"
#include "host/eval/metrics/evaluate.hpp"
#include "host/eval/metrics/score_calibration.hpp"
#include "host/eval/report/colormap.hpp"
#include "host/eval/report/precision_plot.hpp"
#include "host/eval/report/score_plot.hpp"
#include "tests/support/cli_run.hpp"

namespace binpick::eval {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const OperatingPoint kLoose{10, 15};

HypothesisResult right(double score) {
  HypothesisResult r;
  r.score = score, r.translation_pct = 2, r.rotation_deg = 3, r.gt_index = 0;
  return r;
}

// Wrong at the loose point: 40 degrees off.
HypothesisResult wrong(double score) {
  HypothesisResult r = right(score);
  r.rotation_deg = 40;
  return r;
}

// Wrong as a row whose obj_id its image lacks: no match, errors +inf.
HypothesisResult unmatched(double score) {
  HypothesisResult r = right(score);
  r.gt_index = -1, r.translation_pct = r.rotation_deg = kInf;
  return r;
}

TEST(ScoreCalibration, SeparatedScoresKeepNinetyPercentWithNothingWrong) {
  // 10 right with scores 0.91 ... 1.00, 10 wrong with scores 0 ... 0.45.
  const double right_scores[] = {0.91, 0.92, 0.93, 0.94, 0.95, 0.96, 0.97, 0.98, 0.99, 1.0};
  std::vector<HypothesisResult> results;
  for (int i = 0; i < 10; ++i) results.push_back(wrong(0.05 * i));
  for (double s : right_scores) results.push_back(right(s));
  const ScoreCalibration c = calibrate(results, kLoose);
  EXPECT_TRUE(c.any_right);
  EXPECT_EQ(c.hypotheses, 20u);
  EXPECT_EQ(c.right, 10u);
  // Keeping 9 of 10 right ones: the 9th highest right score.
  EXPECT_DOUBLE_EQ(c.threshold, 0.92);
  EXPECT_EQ(c.accepted, 9u);
  EXPECT_EQ(c.accepted_right, 9u);
  EXPECT_EQ(c.accepted_wrong, 0u);
  EXPECT_DOUBLE_EQ(c.kept, 0.9);
  EXPECT_DOUBLE_EQ(c.wrong_fraction, 0.0);
  EXPECT_EQ(c.outside_unit, 0u);
  EXPECT_EQ(calibration_line(c, kLoose),
            "score: threshold 0.92 keeps 90 % of right poses (9 of 10); 0.0 % of the poses it "
            "accepts are wrong (0 of 9)");
}

TEST(ScoreCalibration, InterleavedScoresLetAKnownFractionOfWrongPosesThrough) {
  // Right at 0.95, 0.85, ..., 0.05; wrong at 0.9, 0.8, ..., 0.0, in shuffled order.
  std::vector<HypothesisResult> results;
  const double right_scores[] = {0.95, 0.85, 0.75, 0.65, 0.55, 0.45, 0.35, 0.25, 0.15, 0.05};
  const double wrong_scores[] = {0.9, 0.8, 0.7, 0.6, 0.5, 0.4, 0.3, 0.2, 0.1, 0.0};
  for (int i = 0; i < 10; ++i) {
    results.push_back(i % 2 ? right(right_scores[i]) : wrong(wrong_scores[9 - i]));
    results.push_back(i % 2 ? wrong(wrong_scores[9 - i]) : right(right_scores[i]));
  }
  const ScoreCalibration c = calibrate(results, kLoose);
  // The 9th highest right score is 0.15: it accepts 9 right ones and the 8 wrong ones from 0.2
  // to 0.9.
  EXPECT_DOUBLE_EQ(c.threshold, 0.15);
  EXPECT_EQ(c.accepted, 17u);
  EXPECT_EQ(c.accepted_wrong, 8u);
  EXPECT_DOUBLE_EQ(c.wrong_fraction, 8.0 / 17.0);
  EXPECT_EQ(calibration_line(c, kLoose),
            "score: threshold 0.15 keeps 90 % of right poses (9 of 10); 47.1 % of the poses it "
            "accepts are wrong (8 of 17)");

  // Keeping half: the 5th highest right score, 0.55, lets 0.6 ... 0.9 through.
  const ScoreCalibration half = calibrate(results, kLoose, 0.5);
  EXPECT_DOUBLE_EQ(half.threshold, 0.55);
  EXPECT_EQ(half.accepted_right, 5u);
  EXPECT_EQ(half.accepted_wrong, 4u);

  const ScoreCurve curve = score_curve(results, kLoose);
  ASSERT_EQ(curve.threshold.size(), std::size_t(kScoreSteps) + 1);
  EXPECT_EQ(curve.right, 10u);
  // t = 0: everything; precision 1/2.
  EXPECT_EQ(curve.accepted[0], 20u);
  EXPECT_DOUBLE_EQ(curve.precision[0], 0.5);
  EXPECT_DOUBLE_EQ(curve.kept[0], 1.0);
  // t = 0.5: right 0.55 ... 0.95 (5) and wrong 0.5 ... 0.9 (5): a score equal to the threshold
  // is accepted.
  EXPECT_DOUBLE_EQ(curve.threshold[50], 0.5);
  EXPECT_EQ(curve.accepted[50], 10u);
  EXPECT_DOUBLE_EQ(curve.precision[50], 0.5);
  EXPECT_DOUBLE_EQ(curve.kept[50], 0.5);
  // t = 0.91: only 0.95, right.
  EXPECT_EQ(curve.accepted[91], 1u);
  EXPECT_DOUBLE_EQ(curve.precision[91], 1.0);
  EXPECT_DOUBLE_EQ(curve.kept[91], 0.1);
  // t = 1: nothing accepted; precision is 1 by definition, nothing kept.
  EXPECT_EQ(curve.accepted[100], 0u);
  EXPECT_DOUBLE_EQ(curve.precision[100], 1.0);
  EXPECT_DOUBLE_EQ(curve.kept[100], 0.0);
}

TEST(ScoreCalibration, UnmatchedHypothesesAreWrong) {
  std::vector<HypothesisResult> results{right(0.8), right(0.7), unmatched(0.9), unmatched(0.75)};
  const ScoreCalibration c = calibrate(results, kLoose);
  EXPECT_EQ(c.right, 2u);
  // ceil(0.9 * 2) = 2 right ones: down to 0.7, which accepts both unmatched ones.
  EXPECT_DOUBLE_EQ(c.threshold, 0.7);
  EXPECT_EQ(c.accepted_wrong, 2u);
  EXPECT_DOUBLE_EQ(c.wrong_fraction, 0.5);
}

TEST(ScoreCalibration, TiesAtTheThresholdAreAllAccepted) {
  // 5 right at 0.8, 5 right at 0.6, wrong at 0.7 and 0.6: keeping 9 needs 0.6, and 0.6 accepts
  // all ten right ones and both wrong ones.
  std::vector<HypothesisResult> results{wrong(0.7), wrong(0.6)};
  for (int i = 0; i < 5; ++i) results.push_back(right(0.8)), results.push_back(right(0.6));
  const ScoreCalibration c = calibrate(results, kLoose);
  EXPECT_DOUBLE_EQ(c.threshold, 0.6);
  EXPECT_EQ(c.accepted_right, 10u);
  EXPECT_DOUBLE_EQ(c.kept, 1.0);
  EXPECT_EQ(c.accepted_wrong, 2u);
}

TEST(ScoreCalibration, KeepTimesCountIsNotRoundedUpByItsLastBit) {
  // 0.9 * 70 is 63.000000000000007 in doubles: 63 right ones are enough, not 64.
  std::vector<HypothesisResult> results;
  for (int i = 0; i < 70; ++i) results.push_back(right((i + 1) / 100.0));
  const ScoreCalibration c = calibrate(results, kLoose);
  EXPECT_EQ(c.accepted_right, 63u);
  EXPECT_DOUBLE_EQ(c.threshold, 0.08);
}

// The threshold is the largest keeping the fraction: checked against every distinct score on
// random data, by brute force.
TEST(ScoreCalibration, ThresholdIsTheLargestThatKeepsTheFraction) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> score(0, 1);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<HypothesisResult> results;
    const int n = 1 + int(rng() % 60);
    for (int i = 0; i < n; ++i) {
      const double s = std::round(score(rng) * 20) / 20;  // coarse: many ties
      results.push_back(rng() % 3 ? right(s) : wrong(s));
    }
    for (double keep : {0.9, 0.5, 1.0}) {
      const ScoreCalibration c = calibrate(results, kLoose, keep);
      std::size_t right_total = 0;
      for (const auto& r : results) right_total += correct_at(r, kLoose);
      ASSERT_EQ(c.any_right, right_total > 0);
      if (!right_total) continue;
      const auto kept_at = [&](double t) {
        std::size_t k = 0;
        for (const auto& r : results) k += correct_at(r, kLoose) && r.score >= t;
        return double(k) / double(right_total);
      };
      double best = -1;
      for (const auto& r : results)
        if (kept_at(r.score) >= keep - 1e-12) best = std::max(best, r.score);
      EXPECT_DOUBLE_EQ(c.threshold, best) << "trial " << trial << " keep " << keep;
      std::size_t accepted = 0, accepted_wrong = 0;
      for (const auto& r : results)
        if (r.score >= best) ++accepted, accepted_wrong += !correct_at(r, kLoose);
      EXPECT_EQ(c.accepted, accepted);
      EXPECT_EQ(c.accepted_wrong, accepted_wrong);
    }
  }
}

TEST(ScoreCalibration, NoRightHypothesisHasNoThreshold) {
  const std::vector<HypothesisResult> results{wrong(0.9), wrong(0.3), unmatched(0.5)};
  const ScoreCalibration c = calibrate(results, kLoose);
  EXPECT_FALSE(c.any_right);
  EXPECT_EQ(c.hypotheses, 3u);
  EXPECT_TRUE(std::isnan(c.threshold));
  EXPECT_TRUE(std::isnan(c.wrong_fraction));
  EXPECT_EQ(c.accepted, 0u);
  EXPECT_EQ(calibration_line(c, kLoose),
            "score: none of the 3 hypotheses is right at (10 %, 15 deg), so no threshold to "
            "calibrate");
  const ScoreCurve curve = score_curve(results, kLoose);
  EXPECT_DOUBLE_EQ(curve.precision[0], 0.0);   // all accepted, none right
  EXPECT_DOUBLE_EQ(curve.precision[95], 1.0);  // nothing accepted
  for (double k : curve.kept) EXPECT_EQ(k, 0.0);
}

TEST(ScoreCalibration, EmptyInput) {
  const ScoreCalibration c = calibrate({}, kLoose);
  EXPECT_FALSE(c.any_right);
  EXPECT_EQ(c.hypotheses, 0u);
  EXPECT_TRUE(std::isnan(c.max_score));
  EXPECT_EQ(calibration_line(c, kLoose), "score: no hypotheses to calibrate it on");
  EXPECT_EQ(score_range_warning("ds", c), "");
  const ScoreCurve curve = score_curve({}, kLoose);
  ASSERT_EQ(curve.threshold.size(), 101u);
  for (std::size_t i = 0; i < curve.threshold.size(); ++i) {
    EXPECT_EQ(curve.accepted[i], 0u);
    EXPECT_EQ(curve.precision[i], 1.0);
    EXPECT_EQ(curve.kept[i], 0.0);
  }
  EXPECT_FALSE(plottable(curve));
}

TEST(ScoreCalibration, ScoresOutsideTheUnitIntervalAreFlagged) {
  // An old results file: vote counts.
  const std::vector<HypothesisResult> votes{right(900), right(500), wrong(700), right(300)};
  const ScoreCalibration c = calibrate(votes, kLoose);
  EXPECT_EQ(c.outside_unit, 4u);
  EXPECT_DOUBLE_EQ(c.max_score, 900);
  // Still exact for what the column holds: 3 of 3 right ones kept from 300.
  EXPECT_DOUBLE_EQ(c.threshold, 300);
  EXPECT_EQ(c.accepted_wrong, 1u);
  const std::string w = score_range_warning("sigma 2 % of d", c);
  EXPECT_EQ(w.rfind("sigma 2 % of d: 4 of 4 scores are outside [0, 1] (highest 900)", 0), 0u) << w;
  EXPECT_NE(calibration_line(c, kLoose).find("[scores not in [0, 1]]"), std::string::npos);
  EXPECT_FALSE(plottable(score_curve(votes, kLoose)));

  // 0 and 1 are inside; a hair above 1, a negative score and NaN are not.
  EXPECT_EQ(scores_outside_unit({right(0.0), right(1.0), wrong(0.5)}), 0u);
  EXPECT_EQ(scores_outside_unit({right(1.0000001), right(-0.01), wrong(std::nan(""))}), 3u);
  EXPECT_TRUE(plottable(score_curve({right(0.0), right(1.0)}, kLoose)));
}

TEST(ScoreCalibration, KeptFractionOutsideZeroOneIsAnInputError) {
  EvalOptions o;
  EXPECT_NO_THROW(check(o));
  for (double keep : {0.0, -0.5, 1.5, std::nan("")}) {
    o.score_keep = keep;
    EXPECT_THROW(check(o), InputError) << keep;
  }
}

TEST(ScoreCurve, GridThresholdsAcceptScoresEqualToThem) {
  // A running sum of 0.01 misses 0.29 in its last bits; 29 / 100.0 is the double 0.29.
  const ScoreCurve curve = score_curve({right(0.29), wrong(0.57)}, kLoose);
  EXPECT_EQ(curve.threshold[29], 0.29);
  EXPECT_EQ(curve.accepted[29], 2u);
  EXPECT_EQ(curve.accepted[30], 1u);
  EXPECT_EQ(curve.accepted[57], 1u);
  EXPECT_EQ(curve.accepted[58], 0u);
  EXPECT_DOUBLE_EQ(curve.precision[30], 0.0);
}

TEST(ScoreCurve, CsvHasAQuotedLabelAndOneLinePerPoint) {
  const auto dir = test::fresh_temp_dir("score_curves_csv");
  const std::vector<HypothesisResult> results{right(0.8), wrong(0.4)};
  write_score_curves_csv(dir / "score_curves.csv",
                         {{"a \"b\", c", score_curve(results, kLoose), calibrate(results, kLoose)},
                          {"second", score_curve({}, kLoose), calibrate({}, kLoose)}});
  const std::string csv = test::slurp(dir / "score_curves.csv");
  EXPECT_EQ(csv.rfind("label,threshold,accepted,precision,kept\n", 0), 0u);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 2 * 101);
  EXPECT_NE(csv.find("\n\"a \"\"b\"\", c\",0,2,0.5,1\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n\"a \"\"b\"\", c\",0.5,1,1,1\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n\"second\",1,0,1,0\n"), std::string::npos) << csv;
}

TEST(ScorePlot, LeavesOutCurvesOffTheScoreAxisButKeepsTheColours) {
  const std::vector<HypothesisResult> votes{right(900), wrong(40)};
  const std::vector<HypothesisResult> verified{right(0.9), wrong(0.2)};
  const std::vector<LabelledScoreCurve> curves{
      {"old votes", score_curve(votes, kLoose), calibrate(votes, kLoose)},
      {"verified", score_curve(verified, kLoose), calibrate(verified, kLoose)}};
  const std::string script = score_threshold_script(curves, kLoose);
  EXPECT_EQ(script.find("old votes"), std::string::npos);
  EXPECT_EQ(script.find("$s0"), std::string::npos);
  EXPECT_NE(script.find("$s1 using 1:2 with lines lw 2.5 lc rgb '" + hex(curve_colour(1, 2)) +
                        "' title 'verified'"),
            std::string::npos)
      << script;
  EXPECT_NE(script.find("$s1 using 1:3"), std::string::npos);   // the kept panel
  EXPECT_NE(script.find("$m1 << EOD\n0.9 1 1\nEOD"), std::string::npos) << script;
  // Up to 0.9 the right pose is accepted; above it nothing is, and precision is not drawn.
  EXPECT_NE(script.find("\n0.9 1 1\n0.91 NaN 0\n"), std::string::npos) << script;
  EXPECT_NE(script.find("0.95 with lines dt 2"), std::string::npos);
  EXPECT_NE(script.find("0.9 with lines dt 2"), std::string::npos);
  EXPECT_NE(script.find("multiplot layout 1,2"), std::string::npos);
  EXPECT_THROW(score_threshold_script({curves[0]}, kLoose), std::invalid_argument);
}

}  // namespace
}  // namespace binpick::eval
