#include "host/detect/verify/patch_bias.hpp"

#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

namespace binpick {

ModelPatches model_patches(const PointCloud& model, float size) {
  if (!(size > 0)) throw std::logic_error("patch size must be positive");
  ModelPatches out;
  if (model.points.empty()) return out;
  out.of_point.reserve(model.points.size());
  // The grid starts at the model's lowest corner, not at its origin: the same part gives the
  // same patches wherever its CAD file puts the origin.
  Eigen::Vector3f low = model.points.front();
  for (const Eigen::Vector3f& p : model.points) low = low.cwiseMin(p);
  std::map<std::tuple<long, long, long>, std::uint32_t> cells;
  for (const Eigen::Vector3f& point : model.points) {
    const Eigen::Vector3f p = (point - low) / size;
    const auto cell = std::make_tuple(long(std::floor(p.x())), long(std::floor(p.y())),
                                      long(std::floor(p.z())));
    const auto [it, added] = cells.emplace(cell, out.count);
    if (added) ++out.count;
    out.of_point.push_back(it->second);
  }
  return out;
}

PatchTest patch_test(std::span<const float> residuals, const ModelPatches& patches,
                     const PatchTestOptions& opt) {
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
  PatchTest t;
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
