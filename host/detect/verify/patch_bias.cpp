#include "host/detect/verify/patch_bias.hpp"

#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

namespace binpick {

PatchBias patch_bias(std::span<const float> residuals, const ModelPatches& patches,
                     const PatchBiasOptions& opt) {
  if (residuals.size() != patches.of_point.size())
    throw std::logic_error("patch test: one residual per model point expected");
  std::vector<double> sum(patches.count, 0.0);
  std::vector<std::uint32_t> n(patches.count, 0);
  double all_sum = 0, all_sq = 0;
  std::size_t all_n = 0;
  for (std::size_t j = 0; j < residuals.size(); ++j) {
    const double r = residuals[j];
    if (!std::isfinite(r)) continue;
    sum[patches.of_point[j]] += r;
    ++n[patches.of_point[j]];
    all_sum += r;
    all_sq += r * r;
    ++all_n;
  }
  PatchBias t;
  if (all_n < 2) return t;
  const double mean = all_sum / double(all_n);
  const double variance = std::max(0.0, all_sq / double(all_n) - mean * mean);
  for (std::uint32_t p = 0; p < patches.count; ++p) {
    if (n[p] < opt.min_points) continue;
    ++t.tested;
    const double excess = std::max(0.0, std::fabs(sum[p] / n[p]) - double(opt.dead_band));
    // n excess^2 > z^2 sigma^2: the excess is more than z standard errors of the patch's mean.
    if (double(n[p]) * excess * excess > double(opt.significance) * opt.significance * variance)
      ++t.biased;
  }
  return t;
}

}  // namespace binpick
