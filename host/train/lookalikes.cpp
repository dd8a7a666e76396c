#include "host/train/lookalikes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "host/train/oriented_point_grid.hpp"

namespace binpick {
namespace {

double angle_between_deg(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  const double c = std::clamp(((A.transpose() * B).trace() - 1.0) / 2.0, -1.0, 1.0);
  return std::acos(c) * 180.0 / std::numbers::pi;
}

// Whether R is (within kSameRotationDeg) a rotation the exact symmetries already cover.
bool covered(const Eigen::Matrix3d& R, const PartSymmetries& exact) {
  const Eigen::AngleAxisd aa(R);
  for (const auto& s : exact.continuous)
    if (std::fabs(aa.axis().dot(s.axis.normalized())) >
        std::cos(kSameRotationDeg * std::numbers::pi / 180))
      return true;
  for (const auto& m : exact.discrete)
    if (angle_between_deg(R, m.topLeftCorner<3, 3>()) < kSameRotationDeg) return true;
  return false;
}

}  // namespace

std::vector<Eigen::Isometry3d> find_lookalikes(const PointCloud& model, float voxel_size,
                                                    const PartSymmetries& exact) {
  std::vector<Eigen::Isometry3d> out;
  const std::size_t n = model.points.size();
  if (n < 10 || model.normals.size() != n || !(voxel_size > 0)) return out;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : model.points) c += p.cast<double>();
  c /= double(n);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : model.points) {
    const Eigen::Vector3d d = p.cast<double>() - c;
    cov += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  // Turn about the centre of the points' box in the principal frame, not their centroid: an
  // unmatched feature (a plate's holes) moves the centroid off the outline's centre by
  // millimetres, which refinement cannot remove along a flat part's plane.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (const auto& p : model.points) {
    const Eigen::Vector3d local = eig.eigenvectors().transpose() * (p.cast<double>() - c);
    lo = lo.cwiseMin(local), hi = hi.cwiseMax(local);
  }
  c += eig.eigenvectors() * ((lo + hi) / 2);
  const OrientedPointGrid grid(model, voxel_size, kSameFacingCos);

  std::vector<Eigen::Matrix3d> found;
  for (int axis = 2; axis >= 0; --axis) {
    const Eigen::Vector3d a = eig.eigenvectors().col(axis).normalized();
    for (int fold : {2, 3, 4, 6})
      for (int k = 1; k < fold; ++k) {
        const Eigen::Matrix3d R =
            Eigen::AngleAxisd(2 * std::numbers::pi * k / fold, a).toRotationMatrix();
        if (covered(R, exact)) continue;
        if (std::any_of(found.begin(), found.end(), [&](const Eigen::Matrix3d& F) {
              return angle_between_deg(F, R) < kSameRotationDeg;
            }))
          continue;
        std::size_t matched = 0;
        for (std::size_t i = 0; i < n; ++i) {
          const Eigen::Vector3d q = R * (model.points[i].cast<double>() - c) + c;
          matched += grid.matches(q.cast<float>(), (R * model.normals[i].cast<double>()).cast<float>());
        }
        if (double(matched) >= kLookalikeMatchRatio * double(n)) found.push_back(R);
      }
  }
  for (const auto& R : found) {
    if (out.size() == kMaxLookalikes) break;
    Eigen::Isometry3d S = Eigen::Isometry3d::Identity();
    S.linear() = R;
    S.translation() = c - R * c;
    out.push_back(S);
  }
  return out;
}

}  // namespace binpick
