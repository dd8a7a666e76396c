// Precision as a function of one error threshold (the paper's Figure 7): for each threshold,
// the fraction of hypotheses whose translation (or rotation) error alone is within it, over all
// hypotheses (panels a, c) or over the top-ranked one (highest score) of each image (panels b, d).
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "host/eval/metrics/evaluate.hpp"

namespace binpick::eval {

enum class ErrorKind { translation_pct, rotation_deg };
enum class HypothesisSet { all, top };

struct CurveAxis {
  ErrorKind error;
  double max = 0;     // thresholds from 0 to max inclusive
  int steps = 0;      // max / steps apart
};

// The paper's ranges: translation 0 to 30 % of the diameter, rotation 0 to 60 degrees.
inline constexpr CurveAxis kTranslationAxis{ErrorKind::translation_pct, 30.0, 120};
inline constexpr CurveAxis kRotationAxis{ErrorKind::rotation_deg, 60.0, 120};

struct PrecisionCurve {
  ErrorKind error;
  HypothesisSet set;
  std::vector<double> threshold, precision;  // same length; precision in [0, 1]
};

// One curve; precision 0 everywhere if the set is empty.
PrecisionCurve precision_curve(const std::vector<HypothesisResult>& results, const CurveAxis& axis,
                               HypothesisSet set);

// The four panels in the paper's order: a translation/all, b translation/top, c rotation/all,
// d rotation/top.
std::array<PrecisionCurve, 4> figure7_curves(const std::vector<HypothesisResult>& results);

const char* name(ErrorKind e);     // "translation_pct", "rotation_deg"
const char* name(HypothesisSet s); // "all", "top"

struct LabelledCurves {
  std::string label;  // the dataset's
  std::array<PrecisionCurve, 4> curves;
};

// curves.csv: label,set,error,threshold,precision (one line a point; long format for any tool).
void write_curves_csv(const std::filesystem::path& path, const std::vector<LabelledCurves>& all);

}  // namespace binpick::eval
