#include "host/detect/verify/seen_area.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "host/detect/refine/pose_fit.hpp"  // the point classes (pose_fit_shared.h)

namespace binpick {

double mean_projected_area(std::span<const Eigen::Vector3f> normals) {
  // The golden angle: consecutive points of the spiral turn by it, which spreads them evenly.
  constexpr double kGoldenAngle = 2.399963229728653;
  double total = 0;
  for (int i = 0; i < kAreaDirections; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / kAreaDirections;
    const double across = std::sqrt(std::max(0.0, 1.0 - z * z));
    const Eigen::Vector3d d(across * std::cos(i * kGoldenAngle), across * std::sin(i * kGoldenAngle), z);
    for (const Eigen::Vector3f& n : normals) total += std::max(0.0, -n.cast<double>().dot(d));
  }
  return total / kAreaDirections;
}

double seen_area(std::span<const std::uint8_t> classes, const Eigen::Matrix3d& R,
                 const Eigen::Vector3d& t, std::span<const Eigen::Vector3f> points,
                 std::span<const Eigen::Vector3f> normals) {
  if (classes.size() != points.size() || normals.size() != points.size())
    throw std::logic_error("seen area: one class, point and normal per model point expected");
  double area = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (classes[i] == BP_FIT_HIDDEN) continue;
    const Eigen::Vector3d q = R * points[i].cast<double>() + t;
    const Eigen::Vector3d n = R * normals[i].cast<double>();
    const double c = std::max(0.0, ray_cosine(q, n));
    area += classes[i] == BP_FIT_MISSING ? 0.5 * c : c;
  }
  return area;
}

double area_factor(double share, double scale) {
  if (!(scale > 0)) return 1.0;
  if (!(share > 0)) return 0.0;
  return std::min(1.0, share / scale);
}

}  // namespace binpick
