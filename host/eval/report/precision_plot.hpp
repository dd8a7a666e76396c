// The paper's Figure 7 as one PNG: four panels (translation / rotation threshold, all hypotheses
// / the top-ranked one per image), one curve per dataset, coloured by noise level.
#pragma once

#include <filesystem>
#include <vector>

#include "host/eval/metrics/precision_curves.hpp"
#include "host/eval/report/colormap.hpp"

namespace binpick::eval {

// Curve colour i of n: along viridis from the first dataset to the last, so every plot of the
// report colours a dataset alike.
Rgb curve_colour(std::size_t i, std::size_t n);

// The gnuplot script (without output) for the curves; curves in the order given, coloured
// along viridis from the first to the last (sort datasets by noise for a readable legend).
std::string figure7_script(const std::vector<LabelledCurves>& curves);

// Draws figure7_script(curves) into png with gnuplot. Throws std::runtime_error if gnuplot fails.
void plot_figure7(const std::filesystem::path& gnuplot, const std::filesystem::path& png,
                  const std::vector<LabelledCurves>& curves);

}  // namespace binpick::eval
