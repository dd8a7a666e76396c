// Candidate poses from accumulator peaks (Drost 2010, section 3.3): a peak
// (scene reference point s_r, model point m_r, alpha) is the pose
//   P(m) = R_s^T R_x(alpha) R_m (m - m_r) + s_r,
// where R_m, R_s take the normals n_m, n_s onto +x exactly as bp_ppf_alpha does (rotation about
// n x e_x; a half turn about z for n = -x) and alpha is the centre of the voted bin of
// alpha_s - alpha_m (see kernels/ppf_vote.cl for why this sign). Computed on the host in double:
// a few hundred peaks a hypothesis, microseconds of work next to the voting.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "host/detect/vote/ppf_vote.hpp"
#include "host/core/mesh.hpp"
#include "host/train/ppf_model.hpp"

namespace binpick {

// A model-to-scene pose with the votes behind it.
struct PoseCandidate {
  Eigen::Quaternionf q = Eigen::Quaternionf::Identity();  // unit
  Eigen::Vector3f t = Eigen::Vector3f::Zero();            // mm
  std::uint32_t votes = 0;
};

// The rotation that takes the unit normal n onto +x, in bp_ppf_alpha's convention.
Eigen::Matrix3d rotation_to_x(const Eigen::Vector3d& n);

// R_x(alpha): rotation by alpha about +x, (x, r, 0) -> (x, r cos a, r sin a).
Eigen::Matrix3d rotation_about_x(double alpha);

// The centre of alpha bin b: -pi + (b + 1/2) angle_step.
double alpha_bin_centre(std::uint32_t bin, const bp_ppf_quant& quant);

// One pose per peak, in the order of the peaks. scene is the cloud the peaks were voted on
// (normals need not be unit), refs its reference points (peak.ref indexes refs).
std::vector<PoseCandidate> poses_from_peaks(const std::vector<VotePeak>& peaks,
                                            const PointCloud& scene,
                                            const std::vector<std::uint32_t>& refs,
                                            const PpfModel& model);

}  // namespace binpick
