#include "host/eval/metrics/bop_pose_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Geometry>

#include "host/core/error.hpp"

namespace binpick::eval {
namespace {

void check_inputs(const std::vector<Eigen::Vector3d>& vertices,
                  const std::vector<SymmetryTransform>& symmetries) {
  if (vertices.empty()) throw InputError("a pose error needs a model with at least one vertex");
  if (symmetries.empty()) throw InputError("a pose error needs at least the identity transform");
}

// min over the symmetries of max over the vertices of distance(est(v), copy(v)), where both are
// computed by `place` (3D or projected). The max over a copy's vertices stops as soon as it
// reaches the best copy so far (or the bound): that copy can no longer win, and the minimum is
// unchanged.
template <typename Place>
double min_max_distance(const RigidPose& estimate, const RigidPose& truth,
                        const std::vector<Eigen::Vector3d>& vertices,
                        const std::vector<SymmetryTransform>& symmetries, double bound,
                        Place place) {
  check_inputs(vertices, symmetries);
  std::vector<decltype(place(estimate, vertices[0]))> placed_estimate;
  placed_estimate.reserve(vertices.size());
  for (const auto& v : vertices) placed_estimate.push_back(place(estimate, v));
  double best = bound;
  for (const auto& s : symmetries) {
    const RigidPose copy{truth.R * s.R, truth.R * s.t + truth.t};
    double worst = 0;
    for (std::size_t i = 0; i < vertices.size() && worst < best; ++i)
      worst = std::max(worst, (placed_estimate[i] - place(copy, vertices[i])).norm());
    best = std::min(best, worst);
  }
  return best;
}

}  // namespace

std::vector<SymmetryTransform> bop_symmetry_transforms(const PartSymmetries& symmetries,
                                                      double max_step) {
  if (!(max_step > 0)) throw InputError("the symmetry discretisation step must be positive");
  std::vector<SymmetryTransform> discrete{SymmetryTransform{}};
  for (const auto& m : symmetries.discrete)
    discrete.push_back({m.topLeftCorner<3, 3>(), m.topRightCorner<3, 1>()});

  std::vector<SymmetryTransform> continuous;
  const int steps = static_cast<int>(std::ceil(std::numbers::pi / max_step));
  const double step = 2.0 * std::numbers::pi / steps;
  for (const auto& c : symmetries.continuous)
    for (int i = 0; i < steps; ++i) {
      const Eigen::Matrix3d R =
          Eigen::AngleAxisd(i * step, c.axis.normalized()).toRotationMatrix();
      continuous.push_back({R, c.offset - R * c.offset});
    }
  if (continuous.empty()) return discrete;

  std::vector<SymmetryTransform> combined;
  combined.reserve(discrete.size() * continuous.size());
  for (const auto& d : discrete)
    for (const auto& c : continuous) combined.push_back({c.R * d.R, c.R * d.t + c.t});
  return combined;
}

double mssd(const RigidPose& estimate, const RigidPose& truth,
            const std::vector<Eigen::Vector3d>& vertices,
            const std::vector<SymmetryTransform>& symmetries, double bound) {
  return min_max_distance(estimate, truth, vertices, symmetries, bound,
                          [](const RigidPose& p, const Eigen::Vector3d& v) -> Eigen::Vector3d {
                            return p.R * v + p.t;
                          });
}

double mspd(const RigidPose& estimate, const RigidPose& truth, const Eigen::Matrix3d& K,
            const std::vector<Eigen::Vector3d>& vertices,
            const std::vector<SymmetryTransform>& symmetries, double bound) {
  return min_max_distance(estimate, truth, vertices, symmetries, bound,
                          [&K](const RigidPose& p, const Eigen::Vector3d& v) -> Eigen::Vector2d {
                            const Eigen::Vector3d x = K * (p.R * v + p.t);
                            return x.head<2>() / x.z();
                          });
}

}  // namespace binpick::eval
