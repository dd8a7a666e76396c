#include "host/detect/vote/ppf_pose.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace binpick {

Eigen::Matrix3d rotation_to_x(const Eigen::Vector3d& n) {
  const double s2 = n.y() * n.y() + n.z() * n.z();
  if (s2 > double(BP_PPF_AXIS_SIN2)) {
    const double s = std::sqrt(s2);
    return Eigen::AngleAxisd(std::atan2(s, n.x()), Eigen::Vector3d(0, n.z() / s, -n.y() / s))
        .toRotationMatrix();
  }
  if (n.x() > 0) return Eigen::Matrix3d::Identity();
  return Eigen::Vector3d(-1, -1, 1).asDiagonal();  // half turn about z
}

Eigen::Matrix3d rotation_about_x(double alpha) {
  return Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitX()).toRotationMatrix();
}

double alpha_bin_centre(std::uint32_t bin, const bp_ppf_quant& quant) {
  // 2 pi / n_alpha rather than the float angle_step: the bins tile the full turn exactly.
  return -std::numbers::pi + (bin + 0.5) * (2.0 * std::numbers::pi / quant.n_alpha);
}

std::vector<PoseCandidate> poses_from_peaks(const std::vector<VotePeak>& peaks,
                                            const PointCloud& scene,
                                            const std::vector<std::uint32_t>& refs,
                                            const PpfModel& model) {
  std::vector<PoseCandidate> poses;
  poses.reserve(peaks.size());
  for (const VotePeak& p : peaks) {
    const std::uint32_t ref = refs.at(p.ref);
    const Eigen::Vector3d sr = scene.points.at(ref).cast<double>();
    const Eigen::Vector3d ns = scene.normals.at(ref).cast<double>().normalized();
    const Eigen::Vector3d mr = model.cloud.points.at(p.model_point).cast<double>();
    const Eigen::Vector3d nm = model.cloud.normals.at(p.model_point).cast<double>().normalized();
    const Eigen::Matrix3d R = rotation_to_x(ns).transpose() *
                              rotation_about_x(alpha_bin_centre(p.alpha_bin, model.quant)) *
                              rotation_to_x(nm);
    const Eigen::Vector3d t = sr - R * mr;
    Eigen::Quaterniond q(R);
    q.normalize();
    poses.push_back({q.cast<float>(), t.cast<float>(), p.votes});
  }
  return poses;
}

}  // namespace binpick
