#include "host/detect/verify/lookalike_share.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

#include "host/core/angles.hpp"

namespace binpick {

void lookalike_share(std::vector<VerifiedPose>& poses, const std::vector<std::size_t>& group,
                     const Eigen::Vector3d& centroid, const LookalikeOptions& opt) {
  if (group.size() != poses.size())
    throw std::logic_error("look-alike share: one group per pose expected");
  if (!(opt.weight > 0)) return;
  // The turn's cosine bound: trace(R_i^T R_j) = 1 + 2 cos(angle).
  const double min_trace = 1.0 + 2.0 * std::cos(opt.min_turn_deg * kDeg);
  std::vector<double> fit(poses.size()), best(poses.size(), 0.0);
  for (std::size_t i = 0; i < poses.size(); ++i) fit[i] = poses[i].fit_score();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Vector3d ci = poses[i].R * centroid + poses[i].t;
    for (std::size_t j = 0; j < poses.size(); ++j) {
      if (j == i || group[j] != group[i] || !(fit[j] > best[i])) continue;
      if ((poses[j].R * centroid + poses[j].t - ci).norm() > opt.max_distance) continue;
      if ((poses[i].R.transpose() * poses[j].R).trace() >= min_trace) continue;  // the same way
      best[i] = fit[j];
    }
  }
  // Every share is taken against the fits, before any share.
  for (std::size_t i = 0; i < poses.size(); ++i) {
    poses[i].evidence.lookalike_score = best[i];
    poses[i].breakdown[kLookalikeShare] = lookalike_share_factor(fit[i], best[i], opt.weight);
  }
}

}  // namespace binpick
