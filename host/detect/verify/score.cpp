#include "host/detect/verify/score.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace binpick {
namespace {

constexpr std::array<ScoreFactorInfo, kScoreFactorCount> kFactors = {{
    {"agreement", "verify-tolerance", FactorScope::pose, FactorCombine::multiply,
     "inlier agreement over the visible model points, missing depth counting half"},
    {"see_through", "verify-through", FactorScope::pose, FactorCombine::multiply,
     "model surface where the sensor saw past the part counts against the pose"},
    {"outline", "", FactorScope::pose, FactorCombine::multiply,
     "share of the outline where the measured surface steps down (not for thin parts)"},
    {"patch_bias", "verify-patch", FactorScope::pose, FactorCombine::multiply,
     "share of the model's patches whose residuals average out"},
    {"seen_area", "verify-area", FactorScope::pose, FactorCombine::multiply,
     "the area the pose shows the sensor against the part's mean"},
    {"ray_spread", "verify-ray", FactorScope::poses, FactorCombine::multiply,
     "spread along the rays beyond the image's noise (its best pose's)"},
    {"lookalike_holes", "verify-lookalike-holes", FactorScope::pose, FactorCombine::multiply,
     "the sensor sees through the pose where a look-alike of it has a hole"},
    {"edge_step", "verify-edge", FactorScope::pose, FactorCombine::multiply,
     "a thin part's edges step down to what lies beneath"},
    {"below_floor", "", FactorScope::pose, FactorCombine::zero,
     "0 when more than a tenth of the part lies below the bin's floor"},
    {"rival_cap", "verify-rival", FactorScope::poses, FactorCombine::cap,
     "out-fitted by another pose on the points they share: at most its score times the fits' ratio"},
    {"lookalike_share", "verify-lookalike", FactorScope::poses, FactorCombine::multiply,
     "s / (s + w a), a the best score of the same candidate turned another way round"},
}};

}  // namespace

std::span<const ScoreFactorInfo> score_factors() { return kFactors; }

const char* scope_name(FactorScope scope) {
  return scope == FactorScope::pose ? "pose" : "poses";
}

const char* combine_name(FactorCombine combine) {
  switch (combine) {
    case FactorCombine::multiply: return "multiply";
    case FactorCombine::zero: return "zero";
    case FactorCombine::cap: return "cap";
  }
  return "";
}

double ScoreBreakdown::per_pose() const {
  double s = factor[kAgreement];
  for (std::size_t f = kSeeThrough; f <= kEdgeStep; ++f) s *= factor[f];
  return factor[kBelowFloor] == 0 ? 0.0 : s;
}

double ScoreBreakdown::fit() const {
  const double s = per_pose();
  return factor[kRivalCap] < s ? std::max(0.0, factor[kRivalCap]) : s;
}

double ScoreBreakdown::score() const { return fit() * factor[kLookalikeShare]; }

std::string score_table_markdown() {
  std::string out = "| # | factor | parameter | scope | combines | what it measures |\n";
  out += "| --- | --- | --- | --- | --- | --- |\n";
  for (std::size_t f = 0; f < kScoreFactorCount; ++f) {
    const ScoreFactorInfo& i = kFactors[f];
    out += fmt::format("| {} | `{}` | {} | {} | {} | {} |\n", f + 1, i.name,
                       *i.parameter ? fmt::format("`--{}`", i.parameter) : std::string("–"),
                       scope_name(i.scope), combine_name(i.combine), i.meaning);
  }
  return out;
}

std::string describe_factors(const ScoreBreakdown& b) {
  std::string text = fmt::format("{} {:.3f}", kFactors[kAgreement].name, b[kAgreement]);
  for (std::size_t f = kAgreement + 1; f < kScoreFactorCount; ++f) {
    const double v = b.factor[f];
    const bool neutral = f == kRivalCap ? !std::isfinite(v) : v == 1.0;
    if (!neutral) text += fmt::format(" x {} {:.3f}", kFactors[f].name, v);
  }
  return text;
}

std::string factor_columns(const ScoreBreakdown& b) {
  std::string cells;
  for (std::size_t f = 0; f < kScoreFactorCount; ++f) {
    const double v = b.factor[f];
    cells += f == kRivalCap && !std::isfinite(v) ? std::string(",") : fmt::format(",{:.6f}", v);
  }
  return cells;
}

double score_support(std::uint32_t visible, std::uint32_t missing, double min_support) {
  const double support = double(visible) - 0.5 * double(missing);
  return std::max(support, std::max(min_support, 1.0));
}

double agreement_factor(double agreement, std::uint32_t visible, std::uint32_t missing,
                        double min_support) {
  if (visible == 0 || visible == missing) return 0.0;
  return agreement / score_support(visible, missing, min_support);
}

double see_through_factor(double weight, std::uint32_t see_through, double support) {
  if (!(weight > 0)) return 1.0;
  return std::max(0.0, 1.0 - weight * double(see_through) / support);
}

double outline_factor(std::uint32_t step, std::uint32_t run_on) {
  const std::uint32_t cells = step + run_on;
  return cells > 0 ? double(step) / double(cells) : 1.0;
}

double lookalike_share_factor(double s, double lookalike, double weight) {
  if (!(s > 0 && lookalike > 0)) return 1.0;
  return s / (s + weight * lookalike);
}

}  // namespace binpick
