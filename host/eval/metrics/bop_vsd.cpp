#include "host/eval/metrics/bop_vsd.hpp"

#include <cmath>
#include <string>

#include "host/core/error.hpp"
#include "host/eval/metrics/bop_matching.hpp"
#include "host/formats/bop/depth_distance.hpp"

namespace binpick::eval {
namespace {

void check_silhouette(const PartSilhouette& s, std::size_t pixels, const char* which) {
  if (s.pixels.size() != s.depth_mm.size())
    throw InputError(std::string("VSD: the ") + which + " rendering has " +
                     std::to_string(s.pixels.size()) + " pixels and " +
                     std::to_string(s.depth_mm.size()) + " depths");
  for (std::size_t i = 0; i < s.pixels.size(); ++i)
    if (s.pixels[i] >= pixels || (i > 0 && s.pixels[i] <= s.pixels[i - 1]))
      throw InputError(std::string("VSD: the ") + which +
                       " rendering's pixels are not increasing indices into the image");
}

// visibility._estimate_visib_mask, "bop19", at one pixel the model covers (dist_model > 0).
bool visible(double dist_model, double dist_test, float delta) {
  return float(dist_model) - float(dist_test) <= delta || dist_test == 0;
}

}  // namespace

std::vector<double> bop_vsd_taus() { return arange(0.05, 0.51, 0.05); }
std::vector<double> bop_vsd_thresholds() { return arange(0.05, 0.51, 0.05); }

std::vector<double> vsd_errors(const PartSilhouette& est, const PartSilhouette& gt,
                               const BopDepthImage& test, const Eigen::Matrix3d& K,
                               const VsdSettings& settings) {
  const std::size_t n = std::size_t(test.width) * test.height;
  if (!test.raw || test.raw->size() != n)
    throw InputError("VSD: the depth image does not have " + std::to_string(test.width) + " x " +
                     std::to_string(test.height) + " pixels");
  check_silhouette(est, n, "estimate's");
  check_silhouette(gt, n, "ground truth's");
  const float delta = float(settings.delta_mm);
  const double scale = settings.normalized_by_diameter ? settings.diameter : 1.0;

  // Walk the union of both silhouettes in pixel order; elsewhere neither mask can hold.
  std::vector<double> inter_dists;  // |dist_gt - dist_est| / scale on the intersection
  std::size_t union_count = 0, i = 0, j = 0;
  while (i < est.pixels.size() || j < gt.pixels.size()) {
    const bool take_est = i < est.pixels.size() && (j == gt.pixels.size() || est.pixels[i] <= gt.pixels[j]);
    const bool take_gt = j < gt.pixels.size() && (i == est.pixels.size() || gt.pixels[j] <= est.pixels[i]);
    const std::uint32_t p = take_est ? est.pixels[i] : gt.pixels[j];
    const std::uint32_t u = p % test.width, v = p / test.width;
    const std::uint16_t raw = (*test.raw)[p];
    const double dist_test =
        raw ? bop::distance_of_depth(bop::depth_mm_of_raw(raw, test.depth_scale), u, v, K) : 0.0;
    const double dist_est = take_est ? bop::distance_of_depth(est.depth_mm[i], u, v, K) : 0.0;
    const double dist_gt = take_gt ? bop::distance_of_depth(gt.depth_mm[j], u, v, K) : 0.0;
    const bool visib_gt = dist_gt > 0 && visible(dist_gt, dist_test, delta);
    const bool visib_est = dist_est > 0 && (visible(dist_est, dist_test, delta) || visib_gt);
    union_count += visib_gt || visib_est;
    if (visib_gt && visib_est) inter_dists.push_back(std::abs(dist_gt - dist_est) / scale);
    i += take_est;
    j += take_gt;
  }

  std::vector<double> errors;
  for (double tau : settings.taus) {
    if (union_count == 0) {
      errors.push_back(1.0);
      continue;
    }
    std::size_t costs = 0;
    for (double d : inter_dists) costs += d >= tau;  // the "step" cost
    errors.push_back(double(costs + union_count - inter_dists.size()) / double(union_count));
  }
  return errors;
}

bool sphere_projections_overlap(double radius, const Eigen::Vector3d& p1,
                                const Eigen::Vector3d& p2) {
  if (p1.z() == 0 || p2.z() == 0) return false;
  const Eigen::Vector2d proj1 = (p1 / p1.z()).head<2>(), proj2 = (p2 / p2.z()).head<2>();
  return (proj1 - proj2).norm() < radius * (1.0 / p1.z() + 1.0 / p2.z());
}

}  // namespace binpick::eval
