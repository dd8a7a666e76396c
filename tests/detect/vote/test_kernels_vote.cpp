// The scene-feature and peak kernels of Drost voting (kernels/ppf_vote.cl), each launched by
// itself and compared with a plain C++ reference of that one step
// (tests/support/kernel_refs.hpp), and the routine's sequence features -> vote -> peaks with each
// step checked.
//
// ppf_scene_features: exactly the rows refs[r] of the ppf_pair_features kernel on the same
// buffers (the same bp_ppf_pair8), and the Eigen reference (ppf_pair_feature_reference) up to
// pairs next to a bin edge (kAngleEdgeEps = 1e-4 rad, kDistanceEdgeRel = 1e-5 of max_distance),
// alphas within 1e-4 rad. ppf_peaks: integer, exact, on random accumulators full of ties. The
// composed routine is tests/detect/vote/test_ppf_vote.cpp's.
#include <gtest/gtest.h>

#include <bit>

#include <random>
#include <tuple>

#include "host/detect/vote/ppf_vote.hpp"
#include "host/core/cloud_input.hpp"
#include "host/train/ppf_table.hpp"
#include "tests/support/kernel_refs.hpp"
#include "tests/support/test_device.hpp"

using namespace binpick;
using namespace binpick::test;

namespace {

constexpr u32 kCanary = 0xdeadbeefu;
constexpr std::size_t kGuard = 8;

// Points in a ball with unit normals; every eighth point a copy of an earlier one (coincident
// pairs: no key).
PointCloud random_cloud(std::mt19937& rng, std::size_t n, float radius) {
  std::normal_distribution<float> N(0.0f, 1.0f);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  PointCloud c;
  for (std::size_t i = 0; i < n; ++i) {
    if (i % 8 == 7) c.points.push_back(c.points[i / 2]);
    else c.points.push_back(Eigen::Vector3f(N(rng), N(rng), N(rng)).normalized() * radius * std::cbrt(U(rng)));
    c.normals.push_back(Eigen::Vector3f(N(rng), N(rng), N(rng)));
  }
  return with_unit_normals(c);
}

struct DeviceScene {
  std::size_t n = 0;
  ocl::Buffer<cl_float4> points, normals;
};
DeviceScene on_device(ocl::Device& dev, const PointCloud& c) {
  return {c.points.size(), upload(dev, pack_float4(c.points)), upload(dev, pack_float4(c.normals))};
}

// ppf_pair_features (kernels/ppf_features.cl) on the same buffers: all n x n pairs.
std::pair<std::vector<u32>, std::vector<float>> all_pair_features(ocl::Device& dev,
                                                                  const DeviceScene& s,
                                                                  const bp_ppf_quant& q) {
  ocl::Buffer<u32> keys(dev, s.n * s.n);
  ocl::Buffer<float> alphas(dev, s.n * s.n);
  cl::Kernel k = dev.kernel("ppf_features.cl", "ppf_pair_features");
  ocl::launch(dev, k, s.n, s.points, s.normals, u32(s.n), q, keys, alphas);
  return {keys.read(dev), alphas.read(dev)};
}

// Checks the scene features of refs against the full pair features (exactly) and the Eigen
// reference (up to bin edges); returns the pairs whose key differs from Eigen's.
std::size_t expect_scene_features(const PointCloud& c, const std::vector<u32>& refs,
                                  const bp_ppf_quant& q, const std::vector<u32>& keys,
                                  const std::vector<float>& alphas,
                                  const std::pair<std::vector<u32>, std::vector<float>>& all) {
  const std::size_t n = c.points.size();
  std::size_t at_edge = 0;
  for (std::size_t r = 0; r < refs.size(); ++r)
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t at = r * n + i, full = std::size_t(refs[r]) * n + i;
      EXPECT_EQ(keys[at], all.first[full]) << r << " " << i;
      EXPECT_TRUE(same_bits(alphas[at], all.second[full])) << r << " " << i;
      if (i == refs[r]) {
        EXPECT_EQ(keys[at], BP_PPF_NO_KEY);
        EXPECT_EQ(alphas[at], 0.0f);
        continue;
      }
      const PairFeature f = ppf_pair_feature_reference(c.points[refs[r]], c.normals[refs[r]],
                                                       c.points[i], c.normals[i], q);
      if (keys[at] != f.key) {
        ++at_edge;
        EXPECT_TRUE(ppf_key_difference_at_edge(keys[at], f, q)) << r << " " << i;
      } else if (f.key != BP_PPF_NO_KEY) {
        EXPECT_LT(circular_distance(alphas[at], f.alpha), 1e-4f) << r << " " << i;
        EXPECT_GE(alphas[at], -std::numbers::pi_v<float>);
        EXPECT_LT(alphas[at], std::numbers::pi_v<float>);
      }
      if (keys[at] == BP_PPF_NO_KEY) {
        EXPECT_EQ(alphas[at], 0.0f) << r << " " << i;
      }
    }
  return at_edge;
}

}  // namespace

TEST(VoteKernels, ppf_scene_features_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("ppf_vote.cl", "ppf_scene_features");
  std::mt19937 rng(401);
  std::size_t at_edge = 0, pairs = 0;
  for (auto [n, radius, max_distance] : {std::tuple{400u, 30.0f, 50.0f}, {257u, 40.0f, 30.0f},
                                         {2u, 5.0f, 50.0f}, {1u, 5.0f, 50.0f}}) {
    const bp_ppf_quant q = make_ppf_quant(max_distance, 20, 30);
    const PointCloud c = random_cloud(rng, n, radius);
    const DeviceScene s = on_device(dev, c);
    const auto all = all_pair_features(dev, s, q);
    // Evenly spread (the routine's choice), and random with repeats.
    std::vector<u32> random_refs;
    std::uniform_int_distribution<u32> pick(0, n - 1);
    for (u32 j = 0; j < std::min(n, 37u); ++j) random_refs.push_back(pick(rng));
    for (const std::vector<u32>& refs : {select_reference_points(n, 0.2), random_refs}) {
      ocl::Buffer<u32> ref_buf = upload(dev, refs);
      ocl::Buffer<u32> keys = guarded_buffer(dev, std::vector<u32>(refs.size() * n, kCanary), kGuard, kCanary);
      ocl::Buffer<float> alphas = guarded_buffer(dev, std::vector<float>(refs.size() * n, -9.0f), kGuard, -9.0f);
      ocl::launch_tasks(dev, k, refs.size(), s.points, s.normals, n, ref_buf, u32(refs.size()), q, keys, alphas);
      const std::vector<u32> got_keys = keys.read(dev);
      const std::vector<float> got_alphas = alphas.read(dev);
      for (std::size_t i = refs.size() * n; i < got_keys.size(); ++i) {
        ASSERT_EQ(got_keys[i], kCanary);
        ASSERT_EQ(got_alphas[i], -9.0f);
      }
      at_edge += expect_scene_features(c, refs, q, got_keys, got_alphas, all);
      pairs += refs.size() * n;
    }
  }
  EXPECT_LT(at_edge, pairs / 500 + 1) << at_edge << " of " << pairs;
  std::printf("pairs whose Eigen key differs (at a bin edge): %zu of %zu\n", at_edge, pairs);
}

TEST(VoteKernels, ppf_peaks_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("ppf_vote.cl", "ppf_peaks");
  std::mt19937 rng(402);
  for (auto [count, cells, first_ref] : {std::tuple{1u, 1u, 0u}, {5u, 2u, 0u}, {40u, 30u, 3u},
                                         {33u, 6000u, 0u}, {17u, 450u, 11u}}) {
    // Rows of few distinct vote counts (ties everywhere); row 0 all zero, row 1 one vote in its
    // last cell, row 2 all equal.
    std::vector<u32> acc(std::size_t(count) * cells);
    std::uniform_int_distribution<u32> v(0, 6), z(0, 3);
    for (auto& a : acc) a = z(rng) == 0 ? v(rng) : 0u;
    std::fill_n(acc.begin(), cells, 0u);
    if (count > 1) std::fill_n(acc.begin() + cells, cells, 0u), acc[2 * std::size_t(cells) - 1] = 1;
    if (count > 2) std::fill_n(acc.begin() + 2 * std::size_t(cells), cells, 4u);
    ocl::Buffer<u32> acc_buf = upload(dev, acc);
    // Local maxima along alpha: rows of 30 alpha bins where they divide the cells (else the
    // whole row is one model point's).
    const u32 n_alpha = cells % 30 == 0 ? 30u : cells;
    for (u32 local_max : {0u, 1u})
    for (u32 kk : {1u, 3u, 16u})
      for (float ratio : {0.0f, 0.5f, 0.9f, 1.0f}) {
        const std::size_t slots = std::size_t(first_ref + count) * kk;
        std::vector<cl_uint2> init(slots + kGuard, cl_uint2{{kCanary, kCanary}});
        ocl::Buffer<cl_uint2> peaks = upload(dev, init);
        ocl::launch_tasks(dev, k, count, acc_buf, first_ref, count, cells, kk, ratio, peaks,
                          n_alpha, local_max);
        const std::vector<cl_uint2> got = peaks.read(dev);
        for (std::size_t j = 0; j < got.size(); ++j) {
          const std::size_t row = j / kk;
          if (row < first_ref || row >= first_ref + count) {  // rows of other batches, the guard
            ASSERT_EQ(got[j].s[0], kCanary) << j;
            ASSERT_EQ(got[j].s[1], kCanary) << j;
            continue;
          }
          const std::size_t r = row - first_ref;
          const auto want = ppf_peaks_reference(
              std::span<const u32>(acc.data() + r * cells, cells), kk, ratio,
              local_max ? n_alpha : 0u);
          ASSERT_EQ(got[j].s[0], want[j % kk].first) << "row " << r << " slot " << j % kk << " k " << kk << " ratio " << ratio << " local " << local_max;
          ASSERT_EQ(got[j].s[1], want[j % kk].second) << "row " << r << " slot " << j % kk << " k " << kk << " ratio " << ratio;
        }
      }
  }
}

// The routine's sequence (host/detect/vote/ppf_vote.cpp) in two batches, each step checked on the
// previous step's device output: the features as above, each batch's accumulators exactly
// vote_accumulator_reference, its peaks exactly ppf_peaks_reference; all peaks together are
// vote_peaks_reference's.
TEST(VoteKernels, SequenceFeaturesVotePeaksStepByStep) {
  auto& dev = ocl::Device::shared();
  cl::Kernel features = dev.kernel("ppf_vote.cl", "ppf_scene_features");
  cl::Kernel vote = dev.kernel("ppf_vote.cl", "ppf_vote");
  cl::Kernel find_peaks = dev.kernel("ppf_vote.cl", "ppf_peaks");
  std::mt19937 rng(403);
  PpfModel model;
  model.diameter = 50.0f;
  model.quant = make_ppf_quant(model.diameter, 20, 30);
  model.cloud = random_cloud(rng, 150, 25.0f);
  model.table = build_ppf_table(test_device(), model.cloud, model.quant);
  PointCloud scene = random_cloud(rng, 120, 30.0f);
  for (std::size_t i = 0; i < model.cloud.points.size(); i += 3) {  // part of the model itself
    scene.points.push_back(model.cloud.points[i] + Eigen::Vector3f(1, 2, 3));
    scene.normals.push_back(model.cloud.normals[i]);
  }
  for (int x = 0; x < 8; ++x)  // a flat patch: many equal features, so duplicate votes
    for (int y = 0; y < 8; ++y) {
      scene.points.emplace_back(2.5f * x, 2.5f * y, -20.0f);
      scene.normals.emplace_back(0.0f, 0.0f, 1.0f);
    }
  const std::size_t n = scene.points.size();
  const std::vector<u32> refs = select_reference_points(n, 0.25);
  const DeviceScene s = on_device(dev, scene);
  const DeviceModel dm = upload_model(dev, model);
  ocl::Buffer<u32> ref_buf = upload(dev, refs);
  ocl::Buffer<u32> keys(dev, refs.size() * n);
  ocl::Buffer<float> alphas(dev, refs.size() * n);
  ocl::launch_tasks(dev, features, refs.size(), s.points, s.normals, u32(n), ref_buf, u32(refs.size()),
               model.quant, keys, alphas);
  ScenePairs pairs{n, refs, keys.read(dev), alphas.read(dev)};
  expect_scene_features(scene, refs, model.quant, pairs.keys, pairs.alphas,
                        all_pair_features(dev, s, model.quant));

  const u32 n_model = u32(model.cloud.points.size()), cells = n_model * model.quant.n_alpha;
  std::uint64_t votes_of[3] = {0, 0, 0};  // plain, unique, spread
  for (const int mode : {0, 1, 2}) {
  const bool unique = mode == 1, spread = mode == 2;
  VoteOptions opt{4, 0.5f};
  opt.unique_votes = unique;
  opt.spread_alpha = spread;
  const std::size_t batch = refs.size() / 2 + 1;  // two batches, the second shorter
  const u32 slots = u32(std::bit_ceil(2 * n + 1));
  ocl::Buffer<u32> acc(dev, batch * cells);
  ocl::Buffer<cl_ulong> seen(dev, batch * slots);
  ocl::Buffer<cl_uint2> peak_buf(dev, refs.size() * opt.peaks_per_ref);
  std::vector<VotePeak> got_peaks;
  std::uint64_t& votes = votes_of[mode];
  for (std::size_t first = 0; first < refs.size(); first += batch) {
    const u32 count = u32(std::min(batch, refs.size() - first));
    ocl::launch_tasks(dev, vote, count, keys, alphas, u32(n), u32(first), count, dm.offsets, dm.entries,
                 n_model, model.quant, ppf_vote_inv_step(model.quant), acc, u32(unique), seen, slots, u32(spread));
    const std::vector<u32> got_acc = acc.read(dev, std::size_t(count) * cells);
    for (u32 r = 0; r < count; ++r) {
      const std::vector<u32> want =
          vote_accumulator_reference(pairs, first + r, model, unique, spread);
      ASSERT_TRUE(std::equal(want.begin(), want.end(), got_acc.begin() + std::size_t(r) * cells)) << first + r;
      for (u32 x : want) votes += x;
    }
    ocl::launch_tasks(dev, find_peaks, count, acc, u32(first), count, cells, opt.peaks_per_ref,
                 opt.peak_ratio, peak_buf, model.quant.n_alpha, u32(0));
    const std::vector<cl_uint2> got = peak_buf.read(dev);
    for (u32 r = 0; r < count; ++r) {
      const auto want = ppf_peaks_reference(
          std::span<const u32>(got_acc.data() + std::size_t(r) * cells, cells), opt.peaks_per_ref,
          opt.peak_ratio);
      for (u32 j = 0; j < opt.peaks_per_ref; ++j) {
        const cl_uint2 p = got[(first + r) * opt.peaks_per_ref + j];
        ASSERT_EQ(p.s[0], want[j].first) << first + r << " " << j;
        ASSERT_EQ(p.s[1], want[j].second) << first + r << " " << j;
        if (p.s[1] > 0)
          got_peaks.push_back({u32(first + r), p.s[0] / model.quant.n_alpha,
                               p.s[0] % model.quant.n_alpha, p.s[1]});
      }
    }
  }
  EXPECT_GT(votes, 0u);
  EXPECT_EQ(got_peaks, vote_peaks_reference(pairs, model, opt));
  }
  // Duplicate suppression bites on the flat patch, and leaves most votes.
  EXPECT_LT(votes_of[1], votes_of[0]);
  EXPECT_GT(votes_of[1], votes_of[0] / 4);
  EXPECT_EQ(votes_of[2], 2 * votes_of[0]);  // spreading: every vote twice
}

// Degenerate input: a one-point scene (only the pair with itself), all points coincident (every
// pair skipped), a model without entries for the scene's keys (all-zero accumulators: no peak),
// more peaks wanted than cells exist, and launches in work groups of 16 that do not divide the
// reference points (the extra work items must write nothing).
TEST(VoteKernels, DegenerateScenesAndPaddedWorkGroups) {
  auto& dev = ocl::Device::shared();
  cl::Kernel features = dev.kernel("ppf_vote.cl", "ppf_scene_features");
  cl::Kernel find_peaks = dev.kernel("ppf_vote.cl", "ppf_peaks");
  const bp_ppf_quant q = make_ppf_quant(50.0f, 20, 30);
  std::mt19937 rng(404);
  std::vector<PointCloud> scenes(3);
  scenes[0].points = {{1, 2, 3}};
  scenes[0].normals = {{0, 0, 1}};
  for (int i = 0; i < 21; ++i) scenes[1].points.emplace_back(7, 7, 7), scenes[1].normals.emplace_back(0, 1, 0);
  scenes[2] = random_cloud(rng, 45, 20.0f);
  for (std::size_t c = 0; c < scenes.size(); ++c) {
    const std::size_t n = scenes[c].points.size();
    const DeviceScene s = on_device(dev, scenes[c]);
    std::vector<u32> refs;
    for (u32 r = 0; r < n; r += 2) refs.push_back(r);  // 1, 11 and 23 reference points
    ocl::Buffer<u32> ref_buf = upload(dev, refs);
    ocl::Buffer<u32> keys = guarded_buffer(dev, std::vector<u32>(refs.size() * n, kCanary), kGuard, kCanary);
    ocl::Buffer<float> alphas = guarded_buffer(dev, std::vector<float>(refs.size() * n, -9.0f), kGuard, -9.0f);
    ocl::launch_local(dev, features, refs.size(), 16, s.points, s.normals, u32(n), ref_buf,
                      u32(refs.size()), q, keys, alphas);
    const std::vector<u32> got_keys = keys.read(dev);
    const std::vector<float> got_alphas = alphas.read(dev);
    for (std::size_t i = refs.size() * n; i < got_keys.size(); ++i) {
      ASSERT_EQ(got_keys[i], kCanary) << c;
      ASSERT_EQ(got_alphas[i], -9.0f) << c;
    }
    expect_scene_features(scenes[c], refs, q, got_keys, got_alphas, all_pair_features(dev, s, q));
    if (c < 2) {
      for (std::size_t i = 0; i < refs.size() * n; ++i) EXPECT_EQ(got_keys[i], BP_PPF_NO_KEY) << c;
    }
  }
  // Peaks of all-zero accumulators and of 3 cells with 16 peaks wanted, padded work groups.
  for (auto [count, cells] : {std::pair{5u, 3u}, {19u, 1u}}) {
    std::vector<u32> acc(std::size_t(count) * cells, 0u);
    for (std::size_t i = std::size_t(cells) * 2; i < acc.size(); ++i) acc[i] = u32(i % 2);
    ocl::Buffer<u32> acc_buf = upload(dev, acc);
    ocl::Buffer<cl_uint2> peaks =
        upload(dev, std::vector<cl_uint2>(std::size_t(count) * 16 + kGuard, cl_uint2{{kCanary, kCanary}}));
    ocl::launch_local(dev, find_peaks, count, 16, acc_buf, 0u, count, cells, 16u, 0.0f, peaks,
                      cells, 1u);
    const std::vector<cl_uint2> got = peaks.read(dev);
    for (std::size_t j = 0; j < got.size(); ++j) {
      if (j >= std::size_t(count) * 16) {
        ASSERT_EQ(got[j].s[0], kCanary);
        continue;
      }
      const auto want = ppf_peaks_reference(
          std::span<const u32>(acc.data() + (j / 16) * cells, cells), 16, 0.0f);
      ASSERT_EQ(got[j].s[0], want[j % 16].first) << count << " " << j;
      ASSERT_EQ(got[j].s[1], want[j % 16].second) << count << " " << j;
      if (j < 32) {
        ASSERT_EQ(got[j].s[1], 0u);  // the first two rows have no vote
      }
    }
  }
}
