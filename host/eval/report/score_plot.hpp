// The score calibration as one PNG (score_threshold.png): precision of the accepted poses
// against the score threshold (a) and the fraction of right poses kept (b), one curve per
// dataset coloured as in precision.png, each dataset's calibrated threshold marked, and the
// requirement drawn as dashed lines (95 % precision, 90 % kept). A precision curve ends at the
// last threshold that accepts a pose.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "host/eval/metrics/evaluate.hpp"

namespace binpick::eval {

// True if the curve has something to plot on the [0, 1] score axis: hypotheses, all scores in
// [0, 1].
bool plottable(const ScoreCurve& curve);

// The gnuplot script (without output). Curves in the order given, coloured as curve_colour(i, n)
// over all of them (so as in precision.png); curves that are not plottable are left out but keep
// their colour slot. `at` names the operating point in the title. Throws std::invalid_argument if
// no curve is plottable.
std::string score_threshold_script(const std::vector<LabelledScoreCurve>& curves,
                                   const OperatingPoint& at);

// Draws score_threshold_script into png with gnuplot. Throws std::runtime_error if gnuplot fails.
void plot_score_threshold(const std::filesystem::path& gnuplot, const std::filesystem::path& png,
                          const std::vector<LabelledScoreCurve>& curves, const OperatingPoint& at);

}  // namespace binpick::eval
