// Pose clustering (kernels/pose_cluster.cl + the greedy grouping): the compatibility matrix and
// scores of the device against the C++ reference on random poses (exactly), thresholds that
// bite (translation and rotation, q and -q the same rotation), summed votes and averaged poses.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "host/core/error.hpp"
#include "host/detect/pose_cluster.hpp"

using namespace binpick;

namespace {

constexpr float kDeg = std::numbers::pi_v<float> / 180.0f;

PoseCandidate pose(const Eigen::Quaternionf& q, const Eigen::Vector3f& t, std::uint32_t votes) {
  return {q.normalized(), t, votes};
}

Eigen::Quaternionf turn(float deg, const Eigen::Vector3f& axis) {
  return Eigen::Quaternionf(Eigen::AngleAxisf(deg * kDeg, axis.normalized()));
}

double angle_deg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return 2 * std::acos(std::min(1.0, std::fabs(a.dot(b)))) * 180 / std::numbers::pi;
}

}  // namespace

TEST(PoseCluster, CompatibilityMatchesReferenceExactly) {
  std::mt19937 rng(2);
  std::normal_distribution<float> N(0.0f, 1.0f);
  std::uniform_int_distribution<std::uint32_t> V(1, 50);
  std::vector<PoseCandidate> poses;
  // Groups of poses near a few centres, so many pairs sit near the thresholds.
  for (int c = 0; c < 6; ++c) {
    const Eigen::Quaternionf qc(N(rng), N(rng), N(rng), N(rng));
    const Eigen::Vector3f tc(20 * N(rng), 20 * N(rng), 700 + 20 * N(rng));
    for (int k = 0; k < 120; ++k) {
      Eigen::Quaternionf q = qc.normalized() * turn(12 * std::fabs(N(rng)), {N(rng), N(rng), N(rng)});
      if (k % 3 == 0) q.coeffs() = -q.coeffs();
      poses.push_back(pose(q, tc + 5 * Eigen::Vector3f(N(rng), N(rng), N(rng)), V(rng)));
    }
  }
  auto& dev = ocl::Device::shared();
  const ClusterOptions opt{7.5f, 20.0f};
  const PoseCompatibility got = pose_compatibility(dev, poses, opt);
  const PoseCompatibility want = pose_compatibility_reference(poses, opt);
  EXPECT_EQ(got.compatible, want.compatible);
  EXPECT_EQ(got.scores, want.scores);
  std::size_t ones = 0;
  for (auto c : got.compatible) ones += c;
  EXPECT_GT(ones, poses.size() * 5);                  // groups do form ...
  EXPECT_LT(ones, poses.size() * poses.size() / 6);   // ... and stay apart
  EXPECT_TRUE(pose_compatibility(dev, {}, opt).scores.empty());
}

TEST(PoseCluster, ThresholdsBite) {
  const ClusterOptions opt{7.5f, 20.0f};
  const Eigen::Vector3f t0(0, 0, 800);
  const auto q0 = Eigen::Quaternionf::Identity();
  const float d2 = 7.5f * 7.5f, c = float(std::cos(10.0 * std::numbers::pi / 180));
  const auto a = pose(q0, t0, 1);
  EXPECT_TRUE(pose_compatible(a, pose(turn(19, {1, 2, 3}), t0, 1), d2, c));
  EXPECT_FALSE(pose_compatible(a, pose(turn(21, {1, 2, 3}), t0, 1), d2, c));
  EXPECT_TRUE(pose_compatible(a, pose(q0, t0 + Eigen::Vector3f(7.4f, 0, 0), 1), d2, c));
  EXPECT_FALSE(pose_compatible(a, pose(q0, t0 + Eigen::Vector3f(0, 7.6f, 0), 1), d2, c));
  Eigen::Quaternionf flipped = turn(5, {0, 0, 1});
  flipped.coeffs() = -flipped.coeffs();  // the same rotation
  EXPECT_TRUE(pose_compatible(a, pose(flipped, t0, 1), d2, c));
  EXPECT_THROW(pose_compatibility_reference({a}, {NAN, 20.0f}), InputError);
  EXPECT_THROW(pose_compatibility_reference({a}, {7.5f, 200.0f}), InputError);
  (void)opt;
}

TEST(PoseCluster, GroupsSumVotesAndAverageSignAlignedPoses) {
  auto& dev = ocl::Device::shared();
  const Eigen::Vector3f ta(0, 0, 800), tb(40, 0, 800);
  const Eigen::Quaternionf qa = turn(30, {0, 1, 0});
  std::vector<PoseCandidate> poses;
  // Cluster A: 4 poses, +-4 degrees about z and +-2 mm in x around (qa, ta), two with -q.
  for (int s : {-1, 1})
    for (int flip : {0, 1}) {
      Eigen::Quaternionf q = qa * turn(4.0f * s, {0, 0, 1});
      if (flip) q.coeffs() = -q.coeffs();
      poses.push_back(pose(q, ta + Eigen::Vector3f(2.0f * s, 0, 0), 10));
    }
  // Cluster B: more votes in one pose, but fewer in total; 40 mm away.
  poses.push_back(pose(qa, tb, 25));
  poses.push_back(pose(qa, tb + Eigen::Vector3f(0, 1, 0), 5));
  // A pose 25 degrees off cluster A stays alone.
  poses.push_back(pose(qa * turn(25, {1, 0, 0}), ta, 3));
  const auto clusters = cluster_poses(dev, poses, {7.5f, 20.0f});
  ASSERT_EQ(clusters.size(), 3u);
  EXPECT_EQ(clusters[0].votes, 40u);
  EXPECT_EQ(clusters[0].members, (std::vector<std::uint32_t>{0, 1, 2, 3}));
  EXPECT_LT(angle_deg(clusters[0].q, qa.cast<double>()), 0.05);  // float inputs, acos near 1
  EXPECT_LT((clusters[0].t - ta.cast<double>()).norm(), 1e-4);
  EXPECT_NEAR(clusters[0].q.norm(), 1.0, 1e-12);
  EXPECT_EQ(clusters[1].votes, 30u);
  EXPECT_NEAR(clusters[1].t.y(), 5.0 / 30.0, 1e-5);  // vote-weighted mean
  EXPECT_EQ(clusters[2].votes, 3u);
  EXPECT_EQ(clusters[2].members, (std::vector<std::uint32_t>{6}));
}

TEST(PoseCluster, GreedyIsDeterministicAndCoversEveryPose) {
  std::mt19937 rng(9);
  std::normal_distribution<float> N(0.0f, 1.0f);
  std::vector<PoseCandidate> poses;
  for (int k = 0; k < 400; ++k)
    poses.push_back(pose(Eigen::Quaternionf(1, 0.2f * N(rng), 0.2f * N(rng), 0.2f * N(rng)),
                         Eigen::Vector3f(10 * N(rng), 10 * N(rng), 800), 1 + k % 7));
  auto& dev = ocl::Device::shared();
  const auto a = cluster_poses(dev, poses, {7.5f, 20.0f});
  const auto b = cluster_poses(dev, poses, {7.5f, 20.0f});
  ASSERT_EQ(a.size(), b.size());
  std::vector<int> seen(poses.size(), 0);
  std::uint64_t total = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].members, b[i].members);
    EXPECT_EQ(a[i].q.coeffs(), b[i].q.coeffs());
    if (i > 0) {
      EXPECT_GE(a[i - 1].votes, a[i].votes);
    }
    total += a[i].votes;
    for (auto m : a[i].members) ++seen[m];
  }
  for (int s : seen) EXPECT_EQ(s, 1);
  std::uint64_t want = 0;
  for (const auto& p : poses) want += p.votes;
  EXPECT_EQ(total, want);
}
