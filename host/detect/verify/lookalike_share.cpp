#include "host/detect/verify/lookalike_share.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

#include "host/core/angles.hpp"

namespace binpick {

void lookalike_share(std::vector<RefinedPose>& poses, const std::vector<std::size_t>& group,
                     const Eigen::Vector3d& centroid, const LookalikeOptions& opt) {
  if (group.size() != poses.size())
    throw std::logic_error("look-alike share: one group per pose expected");
  for (RefinedPose& r : poses) r.fit_score = r.score;  // also with the share off
  if (!(opt.weight > 0)) return;
  // The turn's cosine bound: trace(R_i^T R_j) = 1 + 2 cos(angle).
  const double min_trace = 1.0 + 2.0 * std::cos(opt.min_turn_deg * kDeg);
  std::vector<double> best(poses.size(), 0.0);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Vector3d ci = poses[i].R * centroid + poses[i].t;
    for (std::size_t j = 0; j < poses.size(); ++j) {
      if (j == i || group[j] != group[i] || !(poses[j].score > best[i])) continue;
      if ((poses[j].R * centroid + poses[j].t - ci).norm() > opt.max_distance) continue;
      if ((poses[i].R.transpose() * poses[j].R).trace() >= min_trace) continue;  // the same way
      best[i] = poses[j].score;
    }
  }
  // Every share is taken against the scores before any was applied.
  for (std::size_t i = 0; i < poses.size(); ++i) {
    RefinedPose& r = poses[i];
    r.lookalike_score = best[i];
    if (r.score > 0 && best[i] > 0) r.score *= r.score / (r.score + opt.weight * best[i]);
  }
}

}  // namespace binpick
