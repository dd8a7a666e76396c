// Pose clustering (kernels/pose_cluster.cl + the greedy grouping): the compatibility matrix and
// scores of the device against the C++ reference on random poses (exactly), without and with
// the part's symmetries (discrete, a continuous axis, an axis with ends swapped, a sphere);
// thresholds that bite (translation and rotation, q and -q the same rotation); symmetric poses
// compatible; summed votes and averaged poses, poses that differ by a symmetry in one cluster.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "host/core/error.hpp"
#include "host/detect/cluster/pose_cluster.hpp"

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

// Rotation by deg about `axis` through `point`, as the 4x4 of a discrete symmetry.
Eigen::Matrix4d symmetry(float deg, const Eigen::Vector3d& axis, const Eigen::Vector3d& point) {
  const Eigen::Matrix3d R = turn(deg, axis.cast<float>()).toRotationMatrix().cast<double>();
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = R;
  m.topRightCorner<3, 1>() = point - R * point;
  return m;
}

// The bolt's symmetries: sixfold about z through `point`.
PartSymmetries sixfold(const Eigen::Vector3d& point = Eigen::Vector3d::Zero()) {
  PartSymmetries s;
  for (int k = 1; k < 6; ++k) s.discrete.push_back(symmetry(60.0f * k, {0, 0, 1}, point));
  return s;
}

// The shaft's: round about z; with `ends`, also the half turn about x that swaps its ends.
PartSymmetries round_about_z(bool ends) {
  PartSymmetries s;
  s.continuous.push_back({Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero()});
  if (ends) s.discrete.push_back(symmetry(180, {1, 0, 0}, Eigen::Vector3d::Zero()));
  return s;
}

// The pose P o g for a symmetry g of the part: rotation R R_g, translation R t_g + t.
PoseCandidate apply(const PoseCandidate& p, const Eigen::Matrix4d& g) {
  PoseCandidate out = p;
  const Eigen::Quaternionf qg(Eigen::Matrix3f(g.topLeftCorner<3, 3>().cast<float>()));
  out.q = (p.q * qg).normalized();
  out.t = p.t + p.q * g.topRightCorner<3, 1>().cast<float>();
  return out;
}

Eigen::Quaternionf random_quat(std::mt19937& rng) {
  std::normal_distribution<float> N(0.0f, 1.0f);
  return Eigen::Quaternionf(N(rng), N(rng), N(rng), N(rng)).normalized();
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

TEST(PoseCluster, SymmetricCompatibilityMatchesReferenceExactly) {
  std::mt19937 rng(4);
  std::normal_distribution<float> N(0.0f, 1.0f);
  std::uniform_int_distribution<std::uint32_t> V(1, 50);
  // 63 random rotations: the most the kernel takes (no group needed for parity).
  PartSymmetries many;
  for (int k = 0; k < 63; ++k) {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m.topLeftCorner<3, 3>() = random_quat(rng).toRotationMatrix().cast<double>();
    many.discrete.push_back(m);
  }
  PartSymmetries sphere = round_about_z(false);
  sphere.continuous.push_back({Eigen::Vector3d::UnitX(), Eigen::Vector3d::Zero()});
  const std::vector<std::pair<const char*, PartSymmetries>> cases = {
      {"sixfold", sixfold({1, 2, 3})}, {"63 rotations", many}, {"round", round_about_z(false)},
      {"round, ends swapped", round_about_z(true)}, {"sphere", sphere}};
  auto& dev = ocl::Device::shared();
  for (const auto& [name, sym] : cases) {
    // Groups of poses near a few centres, each turned by a symmetry (or any turn about z), so
    // that many pairs are compatible only through a symmetry and many sit near the threshold.
    std::vector<PoseCandidate> poses;
    for (int c = 0; c < 5; ++c) {
      const Eigen::Quaternionf qc = random_quat(rng);
      const Eigen::Vector3f tc(20 * N(rng), 20 * N(rng), 700 + 20 * N(rng));
      for (int k = 0; k < 100; ++k) {
        PoseCandidate p = pose(qc * turn(12 * std::fabs(N(rng)), {N(rng), N(rng), N(rng)}),
                               tc + 5 * Eigen::Vector3f(N(rng), N(rng), N(rng)), V(rng));
        if (!sym.discrete.empty() && k % 2 == 0) {
          PoseCandidate moved = apply(p, sym.discrete[rng() % sym.discrete.size()]);
          p.q = moved.q;  // the posed centre (here t) stays: symmetries keep the centre in place
        }
        if (!sym.continuous.empty() && k % 3 == 0) p.q = p.q * turn(float(rng() % 360), {0, 0, 1});
        if (k % 5 == 0) p.q.coeffs() = -p.q.coeffs();
        poses.push_back(p);
      }
    }
    ClusterOptions opt{7.5f, 20.0f};
    opt.symmetries = sym;
    const PoseCompatibility got = pose_compatibility(dev, poses, opt);
    const PoseCompatibility want = pose_compatibility_reference(poses, opt);
    EXPECT_EQ(got.compatible, want.compatible) << name;
    EXPECT_EQ(got.scores, want.scores) << name;
    const PoseCompatibility plain = pose_compatibility_reference(poses, {7.5f, 20.0f});
    std::size_t with = 0, without = 0;
    for (std::size_t i = 0; i < got.compatible.size(); ++i) {
      with += got.compatible[i];
      without += plain.compatible[i];
      EXPECT_GE(got.compatible[i], plain.compatible[i]) << name;  // symmetries only add pairs
    }
    EXPECT_GT(with, without + poses.size()) << name;  // ... and here, many
  }
}

TEST(PoseCluster, SymmetricPosesAreCompatible) {
  std::mt19937 rng(11);
  const Eigen::Vector3d centre(3, -2, 15);
  const Eigen::Vector3f t0(10, -20, 750);
  ClusterOptions bolt{7.5f, 20.0f};
  bolt.symmetries = sixfold(centre);
  ClusterOptions shaft{7.5f, 20.0f};
  shaft.symmetries = round_about_z(false);
  ClusterOptions ends = shaft;
  ends.symmetries = round_about_z(true);
  for (int trial = 0; trial < 20; ++trial) {
    const PoseCandidate a = pose(random_quat(rng), t0, 1);
    // Each of the bolt's turns, and 3 degrees more (within the angle): compatible; 25 degrees
    // more (between two turns): not.
    for (const Eigen::Matrix4d& g : bolt.symmetries.discrete) {
      PoseCandidate b = apply(a, g);
      b.t = a.t;
      EXPECT_EQ(pose_compatibility_reference({a, b}, bolt).compatible,
                std::vector<std::uint8_t>(4, 1));
      EXPECT_EQ(pose_compatibility_reference({a, b}, {7.5f, 20.0f}).compatible[1], 0);
      b.q = b.q * turn(25, {0, 0, 1});
      EXPECT_EQ(pose_compatibility_reference({a, b}, bolt).compatible[1], 0);
    }
    // Any turn about the shaft's axis; a tilt of the axis by 15 degrees (in) or 25 (out); the
    // ends swapped only when a half turn swaps them.
    const float any = float(rng() % 360);
    const PoseCandidate turned = pose(a.q * turn(any, {0, 0, 1}), t0, 1);
    EXPECT_EQ(pose_compatibility_reference({a, turned}, shaft).compatible[1], 1);
    const PoseCandidate tilted = pose(turned.q * turn(15, {1, 1, 0}), t0, 1);
    EXPECT_EQ(pose_compatibility_reference({a, tilted}, shaft).compatible[1], 1);
    const PoseCandidate far = pose(turned.q * turn(25, {1, 1, 0}), t0, 1);
    EXPECT_EQ(pose_compatibility_reference({a, far}, shaft).compatible[1], 0);
    const PoseCandidate swapped = pose(turned.q * turn(180, {1, 2, 0}), t0, 1);
    EXPECT_EQ(pose_compatibility_reference({a, swapped}, shaft).compatible[1], 0);
    EXPECT_EQ(pose_compatibility_reference({a, swapped}, ends).compatible[1], 1);
    // The translation threshold still bites.
    PoseCandidate away = turned;
    away.t.x() += 8;
    EXPECT_EQ(pose_compatibility_reference({a, away}, shaft).compatible[1], 0);
  }
}

TEST(PoseCluster, PosesThatDifferByASymmetryFormOneCluster) {
  auto& dev = ocl::Device::shared();
  std::mt19937 rng(3);
  // The bolt with its centroid off the origin: its six equivalent poses (and two a few degrees
  // off) are one cluster with all the votes; without symmetries, six clusters.
  const Eigen::Vector3d centre(2, 1, 18);
  const Eigen::Vector3f posed_centre(5, 40, 800);
  const PoseCandidate base =
      pose(random_quat(rng), posed_centre - random_quat(rng) * centre.cast<float>(), 10);
  PoseCandidate first = base;
  first.t = posed_centre - first.q * centre.cast<float>();
  // first turned by deg about y in the model frame, the centroid kept in place.
  auto tilted = [&](float deg) {
    PoseCandidate p = first;
    p.q = (first.q * turn(deg, {0, 1, 0})).normalized();
    p.t = posed_centre - p.q * centre.cast<float>();
    return p;
  };
  std::vector<PoseCandidate> poses{first};
  for (const Eigen::Matrix4d& g : sixfold(centre).discrete) poses.push_back(apply(first, g));
  poses.push_back(apply(tilted(3), sixfold(centre).discrete[1]));
  poses.push_back(tilted(-3));
  ClusterOptions opt{7.5f, 20.0f};
  opt.centre = centre.cast<float>();
  ASSERT_EQ(cluster_poses(dev, poses, opt).size(), 6u);
  opt.symmetries = sixfold(centre);
  const auto clusters = cluster_poses(dev, poses, opt);
  ASSERT_EQ(clusters.size(), 1u);
  EXPECT_EQ(clusters[0].votes, 80u);
  EXPECT_EQ(clusters[0].members.size(), poses.size());
  // The averaged pose is one of the equivalent poses (the +-3 degrees cancel), and puts the
  // centroid where they all put it.
  double nearest = 180;
  for (const PoseCandidate& p : poses)
    nearest = std::min(nearest, angle_deg(clusters[0].q, p.q.cast<double>()));
  EXPECT_LT(nearest, 0.05);
  EXPECT_LT((clusters[0].q * centre + clusters[0].t - posed_centre.cast<double>()).norm(), 1e-3);

  // The shaft: poses turned about its axis by any angle, and one with the ends swapped.
  std::vector<PoseCandidate> round;
  for (float deg : {0.0f, 37.0f, 111.0f, 250.0f, 300.0f}) {
    PoseCandidate p = first;
    p.q = first.q * turn(deg, {0, 0, 1});
    p.t = posed_centre - p.q * centre.cast<float>();
    round.push_back(p);
  }
  PoseCandidate swapped = round[2];
  swapped.q = swapped.q * turn(180, {0, 1, 0});
  swapped.t = posed_centre - swapped.q * centre.cast<float>();
  round.push_back(swapped);
  opt.symmetries = round_about_z(true);
  for (auto& s : opt.symmetries.continuous) s.offset = centre;
  const auto shafts = cluster_poses(dev, round, opt);
  ASSERT_EQ(shafts.size(), 1u);
  EXPECT_EQ(shafts[0].votes, 60u);
  // The axis of the averaged pose is the members' axis, up to its sign.
  const Eigen::Vector3d axis = first.q.cast<double>() * Eigen::Vector3d::UnitZ();
  EXPECT_GT(std::fabs((shafts[0].q * Eigen::Vector3d::UnitZ()).dot(axis)), 1 - 1e-6);
  EXPECT_LT((shafts[0].q * centre + shafts[0].t - posed_centre.cast<double>()).norm(), 1e-3);
  opt.symmetries = round_about_z(false);
  EXPECT_EQ(cluster_poses(dev, round, opt).size(), 2u);  // the swapped one alone
}

TEST(PoseCluster, NearestEquivalentAndBadSymmetries) {
  std::mt19937 rng(8);
  const ClusterSymmetry bolt = cluster_symmetry(sixfold());
  EXPECT_EQ(bolt.mode, BP_CLUSTER_ROTATIONS);
  EXPECT_EQ(bolt.rotations.size(), 5u);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Quaterniond centre = random_quat(rng).cast<double>();
    // centre, tilted by 5 degrees about x, turned by 120 degrees and a few more about z.
    const Eigen::Quaterniond q = centre * turn(5, {1, 0, 0}).cast<double>() *
                                 turn(120 + 4.0f * float(trial % 5), {0, 0, 1}).cast<double>();
    const Eigen::Quaterniond e = nearest_equivalent(q, centre, bolt);
    EXPECT_GE(e.dot(centre), 0);
    // Turned back by 120 degrees: the tilt and the few degrees are left.
    const double left = angle_deg(centre * turn(5, {1, 0, 0}).cast<double>() *
                                      turn(4.0f * float(trial % 5), {0, 0, 1}).cast<double>(),
                                  centre);
    EXPECT_NEAR(angle_deg(e, centre), left, 1e-3);
    const Eigen::Quaterniond round =
        nearest_equivalent(q, centre, cluster_symmetry(round_about_z(false)));
    EXPECT_NEAR(angle_deg(round, centre), 5.0, 1e-3);  // only the tilt is left (float input)
    // The same posed axis: only the turn about it changed.
    EXPECT_LT(((round * Eigen::Vector3d::UnitZ()) - q * Eigen::Vector3d::UnitZ()).norm(), 1e-9);
  }
  EXPECT_EQ(cluster_symmetry(round_about_z(true)).mode, BP_CLUSTER_AXIS_EITHER);
  EXPECT_EQ(cluster_symmetry({}).mode, BP_CLUSTER_ROTATIONS);

  PartSymmetries too_many;
  for (int k = 1; k <= 64; ++k)
    too_many.discrete.push_back(symmetry(5.0f * k, {1, 2, 3}, Eigen::Vector3d::Zero()));
  EXPECT_THROW(cluster_symmetry(too_many), InputError);
  PartSymmetries zero_axis;
  zero_axis.continuous.push_back({Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()});
  ClusterOptions opt{7.5f, 20.0f};
  opt.symmetries = zero_axis;
  EXPECT_THROW(pose_compatibility_reference({}, opt), InputError);
  PartSymmetries sheared;
  sheared.discrete.push_back(Eigen::Matrix4d::Identity());
  sheared.discrete[0](0, 1) = 0.5;
  EXPECT_THROW(cluster_symmetry(sheared), InputError);
}
