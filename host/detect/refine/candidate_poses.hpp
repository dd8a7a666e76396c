// The poses refined for an image: every hypothesis' candidate clusters, each followed by its
// look-alikes (the model's turns that map most of it onto itself, host/train/lookalikes.hpp),
// and, for a thin part, by the pose its in-plane search found (plane_search.hpp) with that
// pose's look-alikes, when the search's edges step down more than the voted pose's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "host/detect/cluster/pose_cluster.hpp"
#include "host/detect/refine/pose_refine.hpp"

namespace binpick {

// Where a refined pose comes from.
struct PoseOrigin {
  std::size_t hypothesis = 0;
  std::uint32_t candidate = 0;  // which of the hypothesis' clusters (0 = most voted)
  std::uint32_t lookalike = 0;  // 0: the pose itself; s: its s-th look-alike
  std::uint64_t votes = 0;      // the cluster's
};

struct CandidatePoses {
  std::vector<PoseToRefine> poses;
  std::vector<PoseOrigin> origin;  // one per pose
  // One group per candidate (hypothesis, cluster): its poses compete as look-alikes.
  std::vector<std::size_t> group;
};

// The clusters' poses in order, hypothesis by hypothesis (as starts for the in-plane search).
std::vector<Eigen::Isometry3d> cluster_poses_in_order(
    const std::vector<std::vector<PoseCluster>>& candidates);

// searched[i]: the in-plane search's pose for the i-th cluster of cluster_poses_in_order, if it
// beat the voted pose (empty: no search).
CandidatePoses expand_candidates(const std::vector<std::vector<PoseCluster>>& candidates,
                                 const std::vector<Eigen::Isometry3d>& lookalikes,
                                 const std::vector<std::optional<Eigen::Isometry3d>>& searched);

}  // namespace binpick
