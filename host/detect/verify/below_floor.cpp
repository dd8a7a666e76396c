#include "host/detect/verify/below_floor.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace binpick {

double fraction_below_floor(const PointCloud& model, const Eigen::Matrix3d& R,
                            const Eigen::Vector3d& t, const Eigen::Vector3d& up, double d,
                            double margin) {
  if (model.points.empty()) return 0.0;
  // up . (R m + t) + d < -margin  <=>  (R^T up) . m < -margin - d - up . t
  const Eigen::Vector3d u = R.transpose() * up;
  const double limit = -margin - d - up.dot(t);
  std::size_t below = 0;
  for (const auto& m : model.points) below += u.dot(m.cast<double>()) < limit;
  return double(below) / double(model.points.size());
}

void mark_below_floor(std::vector<VerifiedPose>& poses, const PointCloud& model, double diameter,
                      const Eigen::Vector3d& up, double d) {
  for (VerifiedPose& v : poses) {
    const double margin = std::max(double(v.evidence.tolerance), 0.1 * diameter);
    const double below = fraction_below_floor(model, v.R, v.t, up, d, margin);
    if (below > kMaxBelowFloor && v.score() > 0) {
      v.breakdown[kBelowFloor] = 0;
      v.reason = fmt::format("{:.0f} % of the part below the bin's floor", 100 * below);
    }
  }
}

}  // namespace binpick
