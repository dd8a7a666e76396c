#include "host/eval/metrics/precision_curves.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "host/core/atomic_file.hpp"

namespace binpick::eval {

const char* name(ErrorKind e) {
  return e == ErrorKind::translation_pct ? "translation_pct" : "rotation_deg";
}
const char* name(HypothesisSet s) { return s == HypothesisSet::all ? "all" : "top"; }

PrecisionCurve precision_curve(const std::vector<HypothesisResult>& results, const CurveAxis& axis,
                               HypothesisSet set) {
  std::vector<double> errors;
  for (const auto& r : results)
    if (set == HypothesisSet::all || r.top)
      errors.push_back(axis.error == ErrorKind::translation_pct ? r.translation_pct : r.rotation_deg);
  std::sort(errors.begin(), errors.end());
  PrecisionCurve c{axis.error, set, {}, {}};
  for (int i = 0; i <= axis.steps; ++i) {
    const double threshold = axis.max * i / axis.steps;
    // Within the threshold means error <= threshold (plus the slack), as in correct_at.
    const auto within =
        std::upper_bound(errors.begin(), errors.end(), threshold + kThresholdSlack) - errors.begin();
    c.threshold.push_back(threshold);
    c.precision.push_back(errors.empty() ? 0.0 : double(within) / double(errors.size()));
  }
  return c;
}

std::array<PrecisionCurve, 4> figure7_curves(const std::vector<HypothesisResult>& results) {
  return {precision_curve(results, kTranslationAxis, HypothesisSet::all),
          precision_curve(results, kTranslationAxis, HypothesisSet::top),
          precision_curve(results, kRotationAxis, HypothesisSet::all),
          precision_curve(results, kRotationAxis, HypothesisSet::top)};
}

void write_curves_csv(const std::filesystem::path& path, const std::vector<LabelledCurves>& all) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "label,set,error,threshold,precision\n";
    for (const auto& lc : all) {
      // Labels are ours or directory names: quote them so a comma cannot shift the columns.
      std::string quoted = "\"";
      for (char ch : lc.label) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
      quoted += '"';
      for (const auto& c : lc.curves)
        for (std::size_t i = 0; i < c.threshold.size(); ++i)
          out << fmt::format("{},{},{},{:g},{:.6g}\n", quoted, name(c.set), name(c.error),
                             c.threshold[i], c.precision[i]);
    }
  });
}

}  // namespace binpick::eval
