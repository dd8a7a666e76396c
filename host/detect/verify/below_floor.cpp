#include "host/detect/verify/below_floor.hpp"

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

}  // namespace binpick
