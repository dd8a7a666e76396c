#include "synth/decompose/convex_parts.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace binpick {

double thinnest_extent(const ConvexHull& hull) {
  const auto& vertices = hull.vertices;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& v : vertices) mean += v.cast<double>();
  mean /= static_cast<double>(vertices.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& v : vertices) {
    const Eigen::Vector3d d = v.cast<double>() - mean;
    covariance += d * d.transpose();
  }
  const Eigen::Matrix3d axes =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (const auto& v : vertices) {
    const Eigen::Vector3d along = axes.transpose() * v.cast<double>();
    lo = lo.cwiseMin(along);
    hi = hi.cwiseMax(along);
  }
  return (hi - lo).minCoeff();
}

}  // namespace binpick
