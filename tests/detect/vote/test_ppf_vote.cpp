// Drost voting (kernels/ppf_vote.cl): the scene features against the Eigen reference, the votes
// and peaks of the device against the C++ reference given the same features (exactly, with and
// without batching), reference point selection, and the model-to-scene alpha convention proved
// on a scene made by moving the model by a known pose.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Geometry>

#include "host/core/error.hpp"
#include "host/detect/detector.hpp"
#include "host/detect/vote/ppf_pose.hpp"
#include "host/detect/vote/ppf_vote.hpp"
#include "host/train/ppf_bucket_cap.hpp"
#include "host/train/ppf_features.hpp"
#include "host/train/ppf_table.hpp"
#include "tests/support/test_device.hpp"

using namespace binpick;
using binpick::test::test_device;

namespace {

// Points in a ball of radius 25 with random unit normals.
PointCloud random_cloud(std::size_t n, std::mt19937& rng, float radius = 25.0f) {
  std::normal_distribution<float> N(0.0f, 1.0f);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  PointCloud c;
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Vector3f d(N(rng), N(rng), N(rng));
    c.points.push_back(d.normalized() * radius * std::cbrt(U(rng)));
    c.normals.push_back(Eigen::Vector3f(N(rng), N(rng), N(rng)).normalized());
  }
  return c;
}

PpfModel random_model(std::size_t n, std::mt19937& rng) {
  PpfModel m;
  m.diameter = 50.0f;
  m.voxel_size = 2.5f;
  m.quant = make_ppf_quant(m.diameter, 20, 30);
  m.cloud = random_cloud(n, rng);
  m.table = build_ppf_table(test_device(), m.cloud, m.quant);
  return m;
}

Eigen::Isometry3f known_pose() {
  Eigen::Isometry3f T = Eigen::Isometry3f::Identity();
  T.linear() = Eigen::AngleAxisf(2.1f, Eigen::Vector3f(0.3f, -0.8f, 0.5f).normalized())
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3f(40.0f, -25.0f, 700.0f);
  return T;
}

}  // namespace

TEST(PpfBucketCap, KeepsEvenlySpacedEntriesOfOverfullBucketsOnly) {
  EXPECT_EQ(bucket_cap_entries(0.0, 318), 0u);
  EXPECT_EQ(bucket_cap_entries(3.0, 318), 954u);
  EXPECT_EQ(bucket_cap_entries(1e-6, 318), 1u);  // a cap keeps at least one entry
  // A plane's pairs: most share a few keys (the case the cap is for).
  PpfModel plate;
  plate.diameter = 50.0f;
  plate.quant = make_ppf_quant(plate.diameter, 20, 30);
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 12; ++x) {
      plate.cloud.points.emplace_back(3.0f * x, 3.0f * y, 0.0f);
      plate.cloud.normals.emplace_back(0.0f, 0.0f, 1.0f);
    }
  const PpfTable& full = plate.table = build_ppf_table(test_device(), plate.cloud, plate.quant);
  const std::size_t cap = 200;
  const PpfTable capped = cap_ppf_buckets(full, cap);
  ASSERT_EQ(capped.offsets.size(), full.offsets.size());
  EXPECT_EQ(capped.offsets.back(), capped.entries.size());
  std::size_t overfull = 0;
  for (std::size_t k = 0; k + 1 < full.offsets.size(); ++k) {
    const std::size_t size = full.offsets[k + 1] - full.offsets[k];
    const std::size_t kept = capped.offsets[k + 1] - capped.offsets[k];
    ASSERT_EQ(kept, std::min(size, cap)) << k;
    if (size > cap) ++overfull;
    for (std::size_t j = 0; j < kept; ++j) {  // floor(j * size / kept), in order
      const bp_ppf_entry& want = full.entries[full.offsets[k] + j * size / kept];
      const bp_ppf_entry& got = capped.entries[capped.offsets[k] + j];
      ASSERT_EQ(got.point, want.point);
      ASSERT_EQ(got.alpha, want.alpha);
    }
  }
  EXPECT_GT(overfull, 0u);
  EXPECT_LT(capped.entries.size(), full.entries.size());
  const PpfTable same = cap_ppf_buckets(full, 0);
  EXPECT_EQ(same.offsets, full.offsets);
  EXPECT_EQ(same.entries.size(), full.entries.size());
  EXPECT_TRUE(cap_ppf_buckets(PpfTable{}, 5).entries.empty());
}

TEST(PpfVote, ReferencePointsAreEvenlySpreadAndDeterministic) {
  EXPECT_TRUE(select_reference_points(0, 0.2).empty());
  EXPECT_EQ(select_reference_points(10, 0.2), (std::vector<std::uint32_t>{0, 5}));
  EXPECT_EQ(select_reference_points(3, 0.01), (std::vector<std::uint32_t>{0}));
  EXPECT_EQ(select_reference_points(4, 1.0), (std::vector<std::uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(select_reference_points(1000, 0.02).size(), 20u);
  EXPECT_THROW(select_reference_points(10, 0.0), InputError);
  EXPECT_THROW(select_reference_points(10, 1.5), InputError);
  EXPECT_THROW(select_reference_points(10, NAN), InputError);
}

TEST(PpfVote, SceneFeaturesMatchReference) {
  std::mt19937 rng(5);
  const PpfModel model = random_model(150, rng);
  const PointCloud scene = random_cloud(300, rng, 30.0f);
  const auto refs = select_reference_points(scene.points.size(), 0.2);
  auto& dev = ocl::Device::shared();
  const DeviceModel dm = upload_model(dev, model);
  ScenePairs got;
  vote_peaks(dev, dm, scene, refs, {}, nullptr, &got);
  const ScenePairs want = scene_pair_features_reference(scene, refs, model.quant);
  ASSERT_EQ(got.keys.size(), want.keys.size());
  std::size_t differ = 0, valid = 0;
  for (std::size_t i = 0; i < got.keys.size(); ++i) {
    if (want.keys[i] != BP_PPF_NO_KEY) ++valid;
    if (got.keys[i] != want.keys[i]) {
      ++differ;  // a value within rounding of a bin edge (bp_atan2_8 vs std::atan2)
      continue;
    }
    if (got.keys[i] == BP_PPF_NO_KEY) continue;
    float d = std::fabs(got.alphas[i] - want.alphas[i]);
    d = std::min(d, 2 * std::numbers::pi_v<float> - d);
    EXPECT_LT(d, 1e-4f) << i;
  }
  EXPECT_GT(valid, got.keys.size() / 4);
  EXPECT_LE(differ, valid / 500 + 1);
}

TEST(PpfVote, VotesAndPeaksMatchReferenceExactly) {
  std::mt19937 rng(7);
  const PpfModel model = random_model(200, rng);
  // Part of the scene is the model itself (so some cells collect many votes), part clutter.
  PointCloud scene = random_cloud(150, rng, 30.0f);
  const Eigen::Isometry3f T = known_pose();
  for (std::size_t i = 0; i < model.cloud.points.size(); i += 2) {
    scene.points.push_back(T * model.cloud.points[i]);
    scene.normals.push_back(T.linear() * model.cloud.normals[i]);
  }
  for (auto& p : scene.points) p -= T.translation();  // near the origin, like the model
  const auto refs = select_reference_points(scene.points.size(), 0.3);
  auto& dev = ocl::Device::shared();
  const DeviceModel dm = upload_model(dev, model);
  for (VoteOptions opt : {VoteOptions{16, 0.0f}, VoteOptions{3, 0.9f}, VoteOptions{1, 1.0f},
                          VoteOptions{3, 0.9f, true}, VoteOptions{3, 0.9f, false, true},
                          VoteOptions{3, 0.5f, false, false, true}}) {
    ScenePairs pairs;
    const auto got = vote_peaks(dev, dm, scene, refs, opt, nullptr, &pairs);
    const auto want = vote_peaks_reference(pairs, model, opt);
    ASSERT_EQ(got.size(), want.size()) << opt.peaks_per_ref;
    for (std::size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i], want[i]) << i;
    // Batches of a few reference points give the same peaks.
    VoteOptions small = opt;
    small.max_accumulator_cells = 7 * model.cloud.points.size() * model.quant.n_alpha;
    EXPECT_EQ(vote_peaks(dev, dm, scene, refs, small), got);
  }
  // A capped table on the device votes as the reference does with the capped table.
  PpfModel capped = model;
  capped.table = cap_ppf_buckets(model.table, 1);
  const DeviceModel dcap = upload_model(dev, model, 1);
  EXPECT_EQ(dcap.bucket_cap, 1u);
  for (VoteOptions opt : {VoteOptions{16, 0.0f}, VoteOptions{3, 0.9f, true, true, true}}) {
    ScenePairs pairs;
    const auto got = vote_peaks(dev, dcap, scene, refs, opt, nullptr, &pairs);
    EXPECT_EQ(got, vote_peaks_reference(pairs, capped, opt));
    EXPECT_NE(got, vote_peaks_reference(pairs, model, opt));  // the cap took votes away
  }
  // Without duplicate suppression every vote lands: the accumulator total is the number of
  // matching table entries; with it, no more.
  ScenePairs pairs;
  vote_peaks(dev, dm, scene, refs, {}, nullptr, &pairs);
  std::uint64_t entries = 0, votes = 0, unique_votes = 0;
  for (std::size_t i = 0; i < pairs.keys.size(); ++i)
    if (pairs.keys[i] != BP_PPF_NO_KEY)
      entries += model.table.offsets[pairs.keys[i] + 1] - model.table.offsets[pairs.keys[i]];
  for (std::size_t r = 0; r < refs.size(); ++r) {
    for (std::uint32_t v : vote_accumulator_reference(pairs, r, model, false)) votes += v;
    for (std::uint32_t v : vote_accumulator_reference(pairs, r, model, true)) unique_votes += v;
  }
  EXPECT_EQ(votes, entries);
  EXPECT_GT(votes, 0u);
  EXPECT_LE(unique_votes, votes);
  EXPECT_GT(unique_votes, votes / 2);
}

TEST(PpfVote, AlphaBinWrapsAroundTheFullTurn) {
  const bp_ppf_quant q = make_ppf_quant(50.0f, 20, 30);
  const float pi = std::numbers::pi_v<float>;
  EXPECT_EQ(ppf_vote_alpha_bin(0.0f, 0.0f, q), 15u);
  EXPECT_EQ(ppf_vote_alpha_bin(3.0f, -3.0f, q), ppf_vote_alpha_bin(6.0f - 2 * pi, 0.0f, q));
  EXPECT_EQ(ppf_vote_alpha_bin(-3.0f, 3.0f, q), ppf_vote_alpha_bin(2 * pi - 6.0f, 0.0f, q));
  EXPECT_EQ(ppf_vote_alpha_bin(-pi, 0.0f, q), 0u);
  for (float a = -pi; a < pi; a += 0.01f)
    for (float b = -pi; b < pi; b += 0.37f) EXPECT_LT(ppf_vote_alpha_bin(a, b, q), 30u);
}

// The vote's bin (an offset worked out at upload, one add in the loop) is the wrapped bin of
// alpha_s - alpha_m in double precision, except within rounding of a bin edge; the spread vote's
// neighbour is the bin on the nearer side; the entries keep their model point's row.
TEST(PpfVote, VoteBinIsTheWrappedDifferenceAwayFromEdges) {
  const bp_ppf_quant q = make_ppf_quant(50.0f, 20, 30);
  const double pi = std::numbers::pi, step = 2 * pi / 30;
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> angle(-float(pi), float(pi));
  std::size_t checked = 0;
  for (int i = 0; i < 200000; ++i) {
    const float s = angle(rng), m = angle(rng);
    double diff = double(s) - double(m);
    if (diff < -pi) diff += 2 * pi;
    if (diff >= pi) diff -= 2 * pi;
    const double u = (diff + pi) / step;
    const double frac = u - std::floor(u);
    if (frac < 1e-4 || frac > 1 - 1e-4) continue;  // next to an edge: either bin
    const auto want = static_cast<std::uint32_t>(std::floor(u)) % 30;
    ASSERT_EQ(ppf_vote_alpha_bin(s, m, q), want) << s << " " << m;
    const std::uint32_t side = frac < 0.5 ? (want + 29) % 30 : (want + 1) % 30;
    if (std::fabs(frac - 0.5) > 1e-4) {  // at a bin's middle: either side
      ASSERT_EQ(ppf_vote_alpha_neighbour(s, m, q), side) << s << " " << m;
    }
    ++checked;
  }
  EXPECT_GT(checked, 199000u);
  const std::vector<bp_ppf_entry> entries = {{0, 0.0f}, {7, -3.0f}, {4, 3.1f}};
  const std::vector<bp_vote_entry> got = vote_entries(entries, q);
  ASSERT_EQ(got.size(), 3u);
  for (std::size_t e = 0; e < entries.size(); ++e) {
    EXPECT_EQ(got[e].row, entries[e].point * 30u);
    float frac = 0;
    EXPECT_EQ(bp_vote_bin(0.25f * ppf_vote_inv_step(q), got[e].offset, 30, &frac),
              ppf_vote_alpha_bin(0.25f, entries[e].alpha, q));
  }
  EXPECT_TRUE(vote_entries({}, q).empty());
}

// The convention proof: moving the model by a known pose, every reference point's best peak
// must be its own model point with an alpha bin whose pose is the known one (to half a bin).
TEST(PpfVote, PeaksOfAMovedModelGiveTheKnownPose) {
  std::mt19937 rng(11);
  const PpfModel model = random_model(250, rng);
  const Eigen::Isometry3f T = known_pose();
  PointCloud scene;
  for (std::size_t i = 0; i < model.cloud.points.size(); ++i) {
    scene.points.push_back(T * model.cloud.points[i]);
    scene.normals.push_back(T.linear() * model.cloud.normals[i]);
  }
  const auto refs = select_reference_points(scene.points.size(), 1.0);
  auto& dev = ocl::Device::shared();
  const DeviceModel dm = upload_model(dev, model);
  const auto peaks = vote_peaks(dev, dm, scene, refs, {1, 1.0f});
  const auto poses = poses_from_peaks(peaks, scene, refs, model);
  ASSERT_EQ(poses.size(), peaks.size());
  std::size_t right = 0;
  const Eigen::Quaternionf qt(T.linear());
  for (std::size_t i = 0; i < peaks.size(); ++i) {
    const float angle = 2 * std::acos(std::min(1.0f, std::fabs(poses[i].q.dot(qt))));
    const float dt = (poses[i].t - T.translation()).norm();
    // half a 12-degree bin, plus rounding; the translation error is that rotation at <= 25 mm
    if (peaks[i].model_point == refs[peaks[i].ref] && angle < 6.2f * std::numbers::pi_v<float> / 180 &&
        dt < 0.11f * 25.0f + 1e-3f)
      ++right;
  }
  EXPECT_GT(right, peaks.size() * 9 / 10) << right << " of " << peaks.size();
}

TEST(PpfVote, BadInputIsAnInputError) {
  std::mt19937 rng(3);
  const PpfModel model = random_model(50, rng);
  auto& dev = ocl::Device::shared();
  const DeviceModel dm = upload_model(dev, model);
  PointCloud scene = random_cloud(20, rng);
  EXPECT_THROW(vote_peaks(dev, dm, scene, {25}, {}), InputError);
  EXPECT_THROW(vote_peaks(dev, dm, scene, {0}, {0, 0.5f}), InputError);
  EXPECT_THROW(vote_peaks(dev, dm, scene, {0}, {17, 0.5f}), InputError);
  scene.points[3].x() = NAN;
  EXPECT_THROW(vote_peaks(dev, dm, scene, {0}, {}), InputError);
  scene = random_cloud(20, rng);
  scene.normals.pop_back();
  EXPECT_THROW(vote_peaks(dev, dm, scene, {0}, {}), InputError);
  EXPECT_TRUE(vote_peaks(dev, dm, PointCloud{}, {}, {}).empty());
}

// The detector builds every program of detection when it is made, so no image's time includes a
// compile; a second detector on the same device builds nothing.
TEST(Detector, BuildsItsProgramsOnceWhenMade) {
  std::mt19937 rng(41);
  const PpfModel m = random_model(60, rng);
  ocl::Device dev;  // a device of its own: nothing is built in it yet
  const Detector first(m, DetectParams{}, dev);
  EXPECT_GT(first.program_build_seconds(), 0.0);
  EXPECT_EQ(dev.prebuild({"depth_to_points.cl", "scene_normals.cl", "ppf_vote.cl", "pose_cluster.cl"}), 0.0);
  const Detector second(m, DetectParams{}, dev);
  EXPECT_EQ(second.program_build_seconds(), 0.0);
}
