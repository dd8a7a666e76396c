#include "host/detect/refine/candidate_poses.hpp"

namespace binpick {

std::vector<Eigen::Isometry3d> cluster_poses_in_order(
    const std::vector<std::vector<PoseCluster>>& candidates) {
  std::vector<Eigen::Isometry3d> starts;
  for (const std::vector<PoseCluster>& clusters : candidates)
    for (const PoseCluster& c : clusters) {
      Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
      start.linear() = c.q.toRotationMatrix();
      start.translation() = c.t;
      starts.push_back(start);
    }
  return starts;
}

CandidatePoses expand_candidates(const std::vector<std::vector<PoseCluster>>& candidates,
                                 const std::vector<Eigen::Isometry3d>& lookalikes,
                                 const std::vector<std::optional<Eigen::Isometry3d>>& searched) {
  CandidatePoses out;
  const std::vector<Eigen::Isometry3d> starts = cluster_poses_in_order(candidates);
  std::size_t next = 0, group = 0;
  const auto add = [&](const Eigen::Isometry3d& pose, const PoseOrigin& from) {
    // Copied out first: the products below are then the same arithmetic whatever the pose's
    // storage (the results are compared bit for bit across versions).
    const Eigen::Matrix3d R = pose.linear();
    const Eigen::Vector3d t = pose.translation();
    out.poses.push_back({R, t});
    out.origin.push_back(from);
    out.group.push_back(group);
    // The pose's look-alikes: model x -> S x, then the pose.
    for (std::uint32_t s = 0; s < lookalikes.size(); ++s) {
      const Eigen::Isometry3d& S = lookalikes[s];
      out.poses.push_back({R * S.linear(), R * S.translation() + t});
      PoseOrigin turned = from;
      turned.lookalike = s + 1;
      out.origin.push_back(turned);
      out.group.push_back(group);
    }
  };
  for (std::size_t k = 0; k < candidates.size(); ++k)
    for (std::uint32_t c = 0; c < candidates[k].size(); ++c, ++next, ++group) {
      const PoseOrigin from{k, c, 0, candidates[k][c].votes};
      add(starts[next], from);
      if (next < searched.size() && searched[next]) add(*searched[next], from);
    }
  return out;
}

}  // namespace binpick
