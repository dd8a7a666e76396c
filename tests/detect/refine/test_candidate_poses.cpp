// The poses refined for an image (refine/candidate_poses.hpp): each cluster, then its
// look-alikes, then the in-plane search's pose and its look-alikes; one group per cluster.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "host/detect/refine/candidate_poses.hpp"

namespace binpick {
namespace {

PoseCluster cluster(double angle, const Eigen::Vector3d& t, std::uint64_t votes) {
  PoseCluster c;
  c.q = Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()));
  c.t = t;
  c.votes = votes;
  return c;
}

TEST(CandidatePoses, ClustersThenTheirLookalikesThenTheSearchedPose) {
  const std::vector<std::vector<PoseCluster>> candidates = {
      {cluster(0.1, {0, 0, 500}, 90), cluster(0.2, {5, 0, 500}, 40)},
      {},
      {cluster(-0.3, {0, 9, 600}, 70)}};
  Eigen::Isometry3d flip = Eigen::Isometry3d::Identity();
  flip.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  flip.translation() = Eigen::Vector3d(0, 2, 0);
  Eigen::Isometry3d found = Eigen::Isometry3d::Identity();
  found.translation() = Eigen::Vector3d(1, 1, 501);
  // The second cluster's search beat its voted pose; the others' did not.
  const std::vector<std::optional<Eigen::Isometry3d>> searched = {std::nullopt, found,
                                                                  std::nullopt};
  const CandidatePoses c = expand_candidates(candidates, {flip}, searched);
  ASSERT_EQ(c.poses.size(), 8u);  // 3 clusters x 2, and the searched pose x 2
  ASSERT_EQ(c.origin.size(), 8u);
  ASSERT_EQ(c.group.size(), 8u);
  const std::vector<std::size_t> hypothesis = {0, 0, 0, 0, 0, 0, 2, 2};
  const std::vector<std::uint32_t> candidate = {0, 0, 1, 1, 1, 1, 0, 0};
  const std::vector<std::uint32_t> lookalike = {0, 1, 0, 1, 0, 1, 0, 1};
  const std::vector<std::size_t> group = {0, 0, 1, 1, 1, 1, 2, 2};
  for (std::size_t i = 0; i < 8; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(c.origin[i].hypothesis, hypothesis[i]);
    EXPECT_EQ(c.origin[i].candidate, candidate[i]);
    EXPECT_EQ(c.origin[i].lookalike, lookalike[i]);
    EXPECT_EQ(c.group[i], group[i]);
  }
  EXPECT_EQ(c.origin[2].votes, 40u);
  EXPECT_EQ(c.origin[4].votes, 40u);  // the searched pose keeps its cluster's votes
  EXPECT_TRUE(c.poses[4].t.isApprox(Eigen::Vector3d(1, 1, 501)));
  // A look-alike is the model turned by S first: x -> R (S x) + t.
  const Eigen::Matrix3d R = candidates[0][0].q.toRotationMatrix();
  EXPECT_TRUE(c.poses[1].R.isApprox(R * flip.linear(), 1e-12));
  EXPECT_TRUE(c.poses[1].t.isApprox(R * flip.translation() + candidates[0][0].t, 1e-12));
  EXPECT_EQ(cluster_poses_in_order(candidates).size(), 3u);
  // Without look-alikes or a search: the clusters alone.
  EXPECT_EQ(expand_candidates(candidates, {}, {}).poses.size(), 3u);
  EXPECT_TRUE(expand_candidates({}, {flip}, {}).poses.empty());
}

}  // namespace
}  // namespace binpick
