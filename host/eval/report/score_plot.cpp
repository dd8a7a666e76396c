#include "host/eval/report/score_plot.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "host/eval/report/gnuplot.hpp"
#include "host/eval/report/precision_plot.hpp"

namespace binpick::eval {

bool plottable(const ScoreCurve& curve) {
  return curve.hypotheses > 0 && curve.outside_unit == 0 && !curve.threshold.empty();
}

std::string score_threshold_script(const std::vector<LabelledScoreCurve>& curves,
                                   const OperatingPoint& at) {
  std::vector<std::size_t> shown;
  for (std::size_t d = 0; d < curves.size(); ++d)
    if (plottable(curves[d].curve)) shown.push_back(d);
  if (shown.empty()) throw std::invalid_argument("no dataset has scores in [0, 1] to plot");
  const double keep = curves[shown.front()].calibration.keep;
  std::string s = fmt::format(
      "set terminal pngcairo size 1400,600 enhanced font 'DejaVu Sans,11'\n"
      "set encoding utf8\n"
      "set multiplot layout 1,2 title {} font ',14'\n"
      "set grid lc rgb '#d0d0d0'\nset xrange [0:1]\nset xtics 0.1\nset yrange [0:1.02]\n"
      "set ytics 0.1\nset xlabel 'score threshold (poses scoring at least it are accepted)'\n"
      "set key bottom left box opaque noenhanced\n",
      gnuplot_quoted(fmt::format("Detection score against right poses at ({:g} %, {:g}°)",
                                 at.translation_pct, at.rotation_deg)));
  // The data as named blocks (threshold, precision, kept), and each calibrated threshold as a
  // one-point block (threshold, 1 - wrong fraction, kept), so the script is self-contained.
  for (std::size_t d : shown) {
    const auto& c = curves[d].curve;
    s += fmt::format("$s{} << EOD\n", d);
    // Where nothing is accepted, precision is 1 by definition, not by measurement: the curve
    // stops there (NaN, which gnuplot leaves out) rather than jump to 1.
    for (std::size_t i = 0; i < c.threshold.size(); ++i)
      s += c.accepted[i] ? fmt::format("{:g} {:.6g} {:.6g}\n", c.threshold[i], c.precision[i],
                                       c.kept[i])
                         : fmt::format("{:g} NaN {:.6g}\n", c.threshold[i], c.kept[i]);
    s += "EOD\n";
    const auto& k = curves[d].calibration;
    if (k.any_right)
      s += fmt::format("$m{} << EOD\n{:.6g} {:.6g} {:.6g}\nEOD\n", d, k.threshold,
                       1 - k.wrong_fraction, k.kept);
  }
  // Panel a: precision, with the requirement (at most 5 % wrong) as a dashed line; panel b: the
  // kept fraction, with the fraction the calibration keeps.
  const struct {
    const char* title;
    const char* ylabel;
    int column;
    double line;
    std::string line_title;
  } panels[2] = {
      {"(a) precision of the accepted poses", "precision (right / accepted)", 2,
       1 - kScoreMaxWrong,
       fmt::format("{:g} % (at most {:g} % wrong)", 100 * (1 - kScoreMaxWrong),
                   100 * kScoreMaxWrong)},
      {"(b) right poses kept", "kept (right accepted / all right)", 3, keep,
       fmt::format("{:g} % kept", 100 * keep)}};
  for (const auto& p : panels) {
    s += fmt::format("set title {}\nset ylabel {}\nplot ", gnuplot_quoted(p.title),
                     gnuplot_quoted(p.ylabel));
    for (std::size_t d : shown) {
      const std::string colour = hex(curve_colour(d, curves.size()));
      s += fmt::format("$s{} using 1:{} with lines lw 2.5 lc rgb '{}' title {}, \\\n     ", d,
                       p.column, colour, gnuplot_quoted(curves[d].label));
      if (curves[d].calibration.any_right)
        s += fmt::format("$m{} using 1:{} with points pt 7 ps 1.6 lc rgb '{}' notitle, \\\n     ",
                         d, p.column, colour);
    }
    s += fmt::format(
        "NaN with points pt 7 ps 1.6 lc rgb '#333333' title {}, \\\n     "
        "{:g} with lines dt 2 lw 1.5 lc rgb '#555555' title {}\n",
        gnuplot_quoted(fmt::format("threshold keeping {:g} % of right poses", 100 * keep)), p.line,
        gnuplot_quoted(p.line_title));
  }
  s += "unset multiplot\n";
  return s;
}

void plot_score_threshold(const std::filesystem::path& gnuplot, const std::filesystem::path& png,
                          const std::vector<LabelledScoreCurve>& curves, const OperatingPoint& at) {
  run_gnuplot_png(gnuplot, score_threshold_script(curves, at), png);
}

}  // namespace binpick::eval
