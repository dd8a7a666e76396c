#include "host/detect/verify/outline.hpp"

#include <algorithm>
#include <limits>

#include <Eigen/Eigenvalues>

namespace binpick {

double thinnest_extent(const PointCloud& model) {
  if (model.points.size() < 3) return 0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3f& p : model.points) mean += p.cast<double>();
  mean /= double(model.points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3f& p : model.points) {
    const Eigen::Vector3d d = p.cast<double>() - mean;
    cov += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);  // ascending
  const Eigen::Vector3d axis = eig.eigenvectors().col(0);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Eigen::Vector3f& p : model.points) {
    const double x = axis.dot(p.cast<double>());
    lo = std::min(lo, x), hi = std::max(hi, x);
  }
  return hi - lo;
}

float outline_ratio_for(const PointCloud& model, double diameter, double tolerance_ratio) {
  return thinnest_extent(model) >= 2 * tolerance_ratio * diameter ? float(tolerance_ratio) : 0.0f;
}

}  // namespace binpick
