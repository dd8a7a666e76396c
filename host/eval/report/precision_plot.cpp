#include "host/eval/report/precision_plot.hpp"

#include <fmt/format.h>

#include "host/eval/report/colormap.hpp"
#include "host/eval/report/gnuplot.hpp"

namespace binpick::eval {
namespace {

constexpr const char* kPanelTitles[4] = {
    "(a) translation threshold, all hypotheses",
    "(b) translation threshold, top-ranked per image",
    "(c) rotation threshold, all hypotheses",
    "(d) rotation threshold, top-ranked per image"};

}  // namespace

// Viridis up to 0.9: its last tenth is too pale on white.
Rgb curve_colour(std::size_t i, std::size_t n) {
  return viridis(n > 1 ? 0.9 * double(i) / double(n - 1) : 0.0);
}

std::string figure7_script(const std::vector<LabelledCurves>& curves) {
  std::string s =
      "set terminal pngcairo size 1400,1000 enhanced font 'DejaVu Sans,11'\n"
      "set encoding utf8\n"
      "set multiplot layout 2,2 title 'Detection precision against error thresholds' "
      "font ',14'\n"
      "set grid lc rgb '#d0d0d0'\nset yrange [0:1.02]\nset ytics 0.1\n"
      "set ylabel 'precision'\nset key bottom right box opaque\n";
  // The data as named blocks, one per dataset and panel, so the script is self-contained.
  for (std::size_t d = 0; d < curves.size(); ++d)
    for (std::size_t p = 0; p < 4; ++p) {
      s += fmt::format("$c{}p{} << EOD\n", d, p);
      const auto& c = curves[d].curves[p];
      for (std::size_t i = 0; i < c.threshold.size(); ++i)
        s += fmt::format("{:g} {:.6g}\n", c.threshold[i], c.precision[i]);
      s += "EOD\n";
    }
  for (std::size_t p = 0; p < 4; ++p) {
    const bool translation = p < 2;
    s += fmt::format("set title {}\n", gnuplot_quoted(kPanelTitles[p]));
    s += translation ? "set xlabel 'translation threshold (% of diameter)'\nset xrange [0:30]\n"
                       "set xtics 5\n"
                     : "set xlabel 'rotation threshold (degrees)'\nset xrange [0:60]\n"
                       "set xtics 10\n";
    s += "plot ";
    for (std::size_t d = 0; d < curves.size(); ++d) {
      if (d) s += ", \\\n     ";
      s += fmt::format("$c{}p{} using 1:2 with lines lw 2.5 lc rgb '{}' title {} noenhanced", d, p,
                       hex(curve_colour(d, curves.size())), gnuplot_quoted(curves[d].label));
    }
    s += "\n";
  }
  s += "unset multiplot\n";
  return s;
}

void plot_figure7(const std::filesystem::path& gnuplot, const std::filesystem::path& png,
                  const std::vector<LabelledCurves>& curves) {
  run_gnuplot_png(gnuplot, figure7_script(curves), png);
}

}  // namespace binpick::eval
