#include "host/detect/verify/ray_spread.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "host/detect/refine/pose_fit.hpp"  // ray_cosine

namespace binpick {

std::vector<double> ray_residuals(std::span<const float> residuals, const Eigen::Matrix3d& R,
                                  const Eigen::Vector3d& t,
                                  std::span<const Eigen::Vector3f> points,
                                  std::span<const Eigen::Vector3f> normals) {
  if (residuals.size() != points.size() || points.size() != normals.size())
    throw std::logic_error("ray test: one residual, point and normal per model point expected");
  std::vector<double> e;
  for (std::size_t j = 0; j < residuals.size(); ++j) {
    if (!std::isfinite(residuals[j])) continue;
    const Eigen::Vector3d q = R * points[j].cast<double>() + t;
    const Eigen::Vector3d nq = R * normals[j].cast<double>();
    const double c = ray_cosine(q, nq);
    // The kernel gives terms only to points facing the camera (within 80 degrees, so 1 / c is
    // at most about 6); a point facing away has no distance along the ray.
    if (!(c > 0.0)) continue;
    e.push_back(double(residuals[j]) / c);
  }
  return e;
}

RaySpread ray_spread(std::span<const double> e) {
  RaySpread s;
  s.n = e.size();
  if (e.empty()) return s;
  double sum = 0;
  for (const double v : e) sum += v * v;
  s.mean_square = sum / double(e.size());
  return s;
}

RaySpread ray_floor(std::span<const RaySpread> poses, std::size_t min_points) {
  RaySpread floor;
  for (const RaySpread& s : poses)
    if (s.n >= std::max<std::size_t>(min_points, 1) &&
        (floor.n == 0 || s.mean_square < floor.mean_square))
      floor = s;
  return floor;
}

double ray_excess(const RaySpread& pose, const RaySpread& floor) {
  if (pose.n == 0 || floor.n == 0) return 0;
  const double inflate = 1.0 + 2.0 * std::sqrt(2.0 / double(pose.n) + 2.0 / double(floor.n));
  return std::sqrt(std::max(0.0, pose.mean_square - floor.mean_square * inflate));
}

}  // namespace binpick
