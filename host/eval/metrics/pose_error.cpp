#include "host/eval/metrics/pose_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Geometry>

namespace binpick::eval {
namespace {

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

// Rigid transform of the model frame onto itself (4x4 with a rotation in the top-left block).
struct Rigid {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
};

// Rotation by theta about the axis through `offset`: x -> C (x - offset) + offset.
Rigid about_axis(const ContinuousSymmetry& s, double theta) {
  Rigid r;
  r.R = Eigen::AngleAxisd(theta, s.axis.normalized()).toRotationMatrix();
  r.t = s.offset - r.R * s.offset;
  return r;
}

bool has_two_axes(const PartSymmetries& symmetries) {
  const auto& c = symmetries.continuous;
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t j = i + 1; j < c.size(); ++j)
      if (c[i].axis.normalized().cross(c[j].axis.normalized()).norm() > 1e-6) return true;
  return false;
}

}  // namespace

double rotation_angle_deg(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  // atan2 of the angle's sine and cosine: acos of the trace alone loses half the digits near 0.
  const Eigen::Matrix3d E = A.transpose() * B;
  const double c = (E.trace() - 1.0) / 2.0;
  const Eigen::Vector3d v(E(2, 1) - E(1, 2), E(0, 2) - E(2, 0), E(1, 0) - E(0, 1));
  const double s = v.norm() / 2.0;
  // Near 180 degrees the skew part vanishes and the sine comes from the trace instead.
  const double angle = c > -0.9 ? std::atan2(s, c) : std::acos(std::clamp(c, -1.0, 1.0));
  return angle * 180.0 / std::numbers::pi;
}

double best_angle_about_axis(const Eigen::Matrix3d& M, const Eigen::Vector3d& axis) {
  const Eigen::Vector3d a = axis.normalized();
  const double along = a.dot(M * a);
  const double cos_term = M.trace() - along;
  const double sin_term = (cross_matrix(a) * M).trace();
  // trace(C(phi) M) = along + cos(phi) cos_term + sin(phi) sin_term is largest at
  // phi = atan2(sin_term, cos_term); C(-theta) = C(phi) gives theta = -phi.
  return -std::atan2(sin_term, cos_term);
}

PoseError symmetric_pose_error(const Eigen::Matrix3d& R_gt, const Eigen::Vector3d& t_gt,
                               const Eigen::Matrix3d& R_est, const Eigen::Vector3d& t_est,
                               const PartSymmetries& symmetries) {
  if (has_two_axes(symmetries))
    return {(t_est - t_gt).norm(), 0.0};  // a sphere: any rotation is right

  std::vector<Rigid> discrete{Rigid{}};
  for (const auto& m : symmetries.discrete)
    discrete.push_back({m.topLeftCorner<3, 3>(), m.topRightCorner<3, 1>()});

  PoseError best{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  for (const Rigid& D : discrete) {
    // Ground-truth copy T_gt * D * C(theta): rotation R_gt D.R C, translation R_gt (D.R c.t + D.t) + t_gt.
    Rigid C;
    const Eigen::Matrix3d RD = R_gt * D.R;
    if (!symmetries.continuous.empty()) {
      const auto& axis = symmetries.continuous.front();
      C = about_axis(axis, best_angle_about_axis(RD.transpose() * R_est, axis.axis));
    }
    const Eigen::Matrix3d R_copy = RD * C.R;
    const Eigen::Vector3d t_copy = R_gt * (D.R * C.t + D.t) + t_gt;
    const PoseError e{(t_est - t_copy).norm(), rotation_angle_deg(R_copy, R_est)};
    // Nearest in rotation; among copies equally near (within rounding), nearest in translation.
    if (e.rotation_deg < best.rotation_deg - 1e-9 ||
        (e.rotation_deg < best.rotation_deg + 1e-9 && e.translation_mm < best.translation_mm))
      best = e;
  }
  return best;
}

}  // namespace binpick::eval
