// The PPF model: point pair features and alpha (kernels/ppf_features.cl), the device hash table
// (kernels/ppf_table.cl) against their C++/Eigen references, degenerate input, training (with the
// part's symmetries) and the .ppfm file (version 4 with symmetries, refinement points and the
// look-alikes' probes, test_lookalike_probes.cpp; versions 1 to 3 still read).
#include <gtest/gtest.h>

#include <limits>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>

#include <Eigen/Geometry>

#include "host/core/error.hpp"
#include "host/train/lookalikes.hpp"
#include "host/train/ppf_features.hpp"
#include "host/train/ppf_model.hpp"
#include "host/train/ppf_model_file.hpp"
#include "host/train/ppf_table.hpp"
#include "host/train/surface_sampling.hpp"
#include "tests/support/test_device.hpp"

using namespace binpick;
using binpick::test::test_device;

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

PointCloud random_cloud(std::mt19937& rng, std::size_t n, float extent) {
  std::uniform_real_distribution<float> u(-extent / 2, extent / 2), c(-1, 1);
  PointCloud cloud;
  for (std::size_t i = 0; i < n; ++i) {
    cloud.points.emplace_back(u(rng), u(rng), u(rng));
    cloud.normals.push_back(Eigen::Vector3f(c(rng), c(rng), c(rng)).normalized());
  }
  return cloud;
}

// An axis-aligned box of size s, 2 triangles a face, counter-clockwise from outside.
Mesh box_mesh(Eigen::Vector3f s) {
  Mesh m;
  for (int i = 0; i < 8; ++i)
    m.positions.emplace_back(i & 1 ? s.x() : 0, i & 2 ? s.y() : 0, i & 4 ? s.z() : 0);
  const std::uint32_t q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                 {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (auto& f : q) {
    m.triangles.push_back({f[0], f[1], f[2]});
    m.triangles.push_back({f[0], f[2], f[3]});
  }
  return m;
}

// Whether value lies within eps of a multiple of step (a bin boundary).
bool near_edge(float value, float step, float eps) {
  const float r = value / step;
  return std::fabs(r - std::round(r)) * step <= eps;
}

struct KeyParts {
  std::uint32_t d, a1, a2, a3;
};
KeyParts split(std::uint32_t key, const bp_ppf_quant& q) {
  KeyParts k;
  k.a3 = key % q.n_angle, key /= q.n_angle;
  k.a2 = key % q.n_angle, key /= q.n_angle;
  k.a1 = key % q.n_angle, k.d = key / q.n_angle;
  return k;
}

float circular_distance(float a, float b) {
  float d = std::fabs(a - b);
  return std::min(d, 2 * kPi - d);
}

// The message parse_ppf_model refuses the bytes with, or "no error".
std::string parse_message(const std::string& bytes) {
  try {
    parse_ppf_model(bytes, "x.ppfm");
  } catch (const InputError& e) {
    return std::string(e.what());
  }
  return std::string("no error");
}

}  // namespace

TEST(PpfQuant, PaperParametersAndBadValues) {
  const bp_ppf_quant q = make_ppf_quant(52.0f, 20, 30);
  EXPECT_EQ(q.n_dist, 20u);
  EXPECT_EQ(q.n_angle, 15u);
  EXPECT_EQ(q.n_alpha, 30u);
  EXPECT_FLOAT_EQ(q.dist_step, 2.6f);
  EXPECT_FLOAT_EQ(q.angle_step, 12.0f * kPi / 180);
  EXPECT_EQ(bp_ppf_key_count(q), 20u * 15 * 15 * 15);
  EXPECT_EQ(bp_ppf_alpha_bin(-kPi, q), 0u);
  EXPECT_EQ(bp_ppf_alpha_bin(0.0f, q), 15u);
  EXPECT_EQ(bp_ppf_alpha_bin(std::nextafter(kPi, 0.0f), q), 29u);
  for (float d : {0.0f, -1.0f, NAN, INFINITY}) EXPECT_THROW(make_ppf_quant(d, 20, 30), InputError);
  EXPECT_THROW(make_ppf_quant(1, 0, 30), InputError);
  EXPECT_THROW(make_ppf_quant(1, 1000000, 30), InputError);
  EXPECT_THROW(make_ppf_quant(1, 20, 0), InputError);
  EXPECT_THROW(make_ppf_quant(1, 20, 1000000), InputError);
  EXPECT_THROW(make_ppf_quant(1, 1000, 360), InputError);  // 1000 * 180^3 keys
}

TEST(PpfFeatures, AlphaConvention) {
  const Eigen::Vector3f x = Eigen::Vector3f::UnitX(), y = Eigen::Vector3f::UnitY(),
                        z = Eigen::Vector3f::UnitZ();
  EXPECT_FLOAT_EQ(ppf_alpha_reference(x, y), 0.0f);
  EXPECT_FLOAT_EQ(ppf_alpha_reference(x, z), kPi / 2);
  EXPECT_FLOAT_EQ(ppf_alpha_reference(x, -z), -kPi / 2);
  EXPECT_FLOAT_EQ(ppf_alpha_reference(x, -y), -kPi);  // pi wraps to -pi
  EXPECT_EQ(ppf_alpha_reference(x, x), 0.0f);          // on the normal's line: defined as 0
  // The difference of two alphas of one reference point does not depend on the pose: that is
  // what detection's voting relies on.
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> c(-1, 1);
  for (int t = 0; t < 200; ++t) {
    const Eigen::Vector3f n = Eigen::Vector3f(c(rng), c(rng), c(rng)).normalized();
    const Eigen::Vector3f d1(c(rng), c(rng), c(rng)), d2(c(rng), c(rng), c(rng));
    const Eigen::Matrix3f r = Eigen::Quaternionf::UnitRandom().toRotationMatrix();
    const float before = ppf_alpha_reference(n, d1) - ppf_alpha_reference(n, d2);
    const float after = ppf_alpha_reference(r * n, r * d1) - ppf_alpha_reference(r * n, r * d2);
    EXPECT_LT(circular_distance(before, after), 1e-3f);
  }
}

TEST(PpfFeatures, MatchReferenceExceptAtBinEdges) {
  std::mt19937 rng(5);
  const PointCloud cloud = random_cloud(rng, 400, 50.0f);
  const bp_ppf_quant q = make_ppf_quant(40.0f, 20, 30);  // some pairs are farther: skipped
  const PairFeatures got = ppf_pair_features(test_device(), cloud, q);
  const PairFeatures want = ppf_pair_features_reference(cloud, q);
  ASSERT_EQ(got.keys.size(), 400u * 400u);
  std::size_t key_mismatches = 0, skipped = 0;
  const float eps = 1e-4f;
  for (std::size_t r = 0; r < 400; ++r)
    for (std::size_t i = 0; i < 400; ++i) {
      const std::size_t k = r * 400 + i;
      skipped += want.keys[k] == BP_PPF_NO_KEY;
      const PairFeature f = ppf_pair_feature_reference(cloud.points[r], cloud.normals[r],
                                                       cloud.points[i], cloud.normals[i], q);
      if (got.keys[k] != want.keys[k]) {
        ++key_mismatches;
        if (got.keys[k] == BP_PPF_NO_KEY || want.keys[k] == BP_PPF_NO_KEY) {
          EXPECT_NEAR(f.f[0], q.max_distance, eps * q.max_distance) << r << " " << i;
          continue;
        }
        const KeyParts a = split(got.keys[k], q), b = split(want.keys[k], q);
        if (a.d != b.d) {
          EXPECT_TRUE(near_edge(f.f[0], q.dist_step, eps * 50)) << f.f[0];
        }
        if (a.a1 != b.a1) {
          EXPECT_TRUE(near_edge(f.f[1], q.angle_step, eps)) << f.f[1];
        }
        if (a.a2 != b.a2) {
          EXPECT_TRUE(near_edge(f.f[2], q.angle_step, eps)) << f.f[2];
        }
        if (a.a3 != b.a3) {
          EXPECT_TRUE(near_edge(f.f[3], q.angle_step, eps)) << f.f[3];
        }
      }
      if (want.keys[k] != BP_PPF_NO_KEY) {
        EXPECT_LT(circular_distance(got.alphas[k], want.alphas[k]), eps) << r << " " << i;
        EXPECT_GE(got.alphas[k], -kPi);
        EXPECT_LT(got.alphas[k], kPi);
      }
    }
  EXPECT_GT(skipped, 400u * 2);         // the diagonal and the far pairs
  EXPECT_LT(skipped, 400u * 400u / 2);  // but not most pairs
  EXPECT_LT(key_mismatches, 400u * 400u / 1000) << key_mismatches;
  std::printf("feature key mismatches at bin edges: %zu of %u pairs\n", key_mismatches, 400 * 400);
}

TEST(PpfFeatures, DegenerateInput) {
  const bp_ppf_quant q = make_ppf_quant(10.0f, 20, 30);
  PointCloud c;
  // 0 and 1 coincide; 2 has the normal of 0 (parallel normals) along d = p2 - p0. 1 and 4 have
  // normals +x and -x, the rotation's special cases; 3 lies on 1's normal line.
  c.points = {{0, 0, 0}, {0, 0, 0}, {0, 0, 5}, {3, 0, 0}, {0, 4, 0}};
  c.normals = {{0, 0, 1}, {1, 0, 0}, {0, 0, 1}, {0, 0, -1}, {-1, 0, 0}};
  const std::size_t n = c.points.size();
  const PairFeatures device = ppf_pair_features(test_device(), c, q);
  const PairFeatures reference = ppf_pair_features_reference(c, q);
  for (const PairFeatures& f : {device, reference}) {
    EXPECT_EQ(f.keys[0 * n + 1], BP_PPF_NO_KEY);  // coincident: skipped both ways
    EXPECT_EQ(f.keys[1 * n + 0], BP_PPF_NO_KEY);
    for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(f.keys[i * n + i], BP_PPF_NO_KEY);
    // 0 -> 2: |d| = 5 (bin 10), n0 parallel to d, n2 parallel to d, normals parallel.
    EXPECT_EQ(f.keys[0 * n + 2], bp_ppf_key(10, 0, 0, 0, q.n_angle));
    EXPECT_EQ(f.alphas[0 * n + 2], 0.0f);  // m_i on n_r's line
    // 0 -> 3: |d| = 3 (bin 6), both normals at pi/2 from d, normals opposite (angle pi: last bin).
    EXPECT_EQ(f.keys[0 * n + 3], bp_ppf_key(6, 7, 7, 14, q.n_angle));
    EXPECT_EQ(f.alphas[1 * n + 3], 0.0f);                   // on +x's line
    EXPECT_NEAR(f.alphas[1 * n + 2], kPi / 2, 1e-6f);         // n = +x: R is the identity
    EXPECT_NEAR(f.alphas[4 * n + 2], std::atan2(5.0f, 4.0f), 1e-6f);  // n = -x: a half turn about z
  }
  // Every pair, the device's eight-lane feature and the Eigen reference alike (none lies within
  // rounding of a bin edge but the exact distances 3 and 5, which both compute exactly).
  for (std::size_t k = 0; k < n * n; ++k) {
    EXPECT_EQ(device.keys[k], reference.keys[k]) << k / n << " -> " << k % n;
    EXPECT_LT(circular_distance(device.alphas[k], reference.alphas[k]), 1e-6f) << k / n << " -> " << k % n;
  }
  PointCloud one;
  one.points = {{1, 2, 3}};
  one.normals = {{0, 1, 0}};
  EXPECT_EQ(ppf_pair_features(test_device(), one, q).keys, std::vector<std::uint32_t>{BP_PPF_NO_KEY});
  EXPECT_TRUE(ppf_pair_features(test_device(), PointCloud{}, q).keys.empty());
}

TEST(PpfFeatures, BadInputIsAnInputError) {
  const bp_ppf_quant q = make_ppf_quant(10.0f, 20, 30);
  PointCloud c;
  c.points = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_THROW(ppf_pair_features(test_device(), c, q), InputError);  // no normals
  c.normals = {{0, 0, 1}, {0, 0, 0}};
  EXPECT_THROW(ppf_pair_features(test_device(), c, q), InputError);  // zero normal
  c.normals = {{0, 0, 1}, {0, NAN, 1}};
  EXPECT_THROW(ppf_pair_features(test_device(), c, q), InputError);
  EXPECT_THROW(build_ppf_table(test_device(), c, q), InputError);
  c.normals = {{0, 0, 1}, {0, 0, 1}};
  c.points[1].x() = NAN;
  EXPECT_THROW(build_ppf_table(test_device(), c, q), InputError);
  EXPECT_THROW(build_ppf_table_reference(c, q), InputError);
}

TEST(PpfTable, EqualsTheTableOfTheDeviceFeaturesExactly) {
  std::mt19937 rng(6);
  const bp_ppf_quant q = make_ppf_quant(45.0f, 20, 30);
  PointCloud cloud = random_cloud(rng, 600, 50.0f);
  // Many equal features: a planar grid with one normal fills few, large buckets.
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) {
      cloud.points.emplace_back(float(i), float(j), 30.0f);
      cloud.normals.emplace_back(0, 0, 1);
    }
  PpfTableTimes times;
  const PpfTable got = build_ppf_table(test_device(), cloud, q, &times);
  const PpfTable want = ppf_table_from_features(ppf_pair_features(test_device(), cloud, q), q);
  ASSERT_EQ(got.offsets, want.offsets);
  ASSERT_EQ(got.entries.size(), want.entries.size());
  for (std::size_t e = 0; e < got.entries.size(); ++e) {
    ASSERT_EQ(got.entries[e].point, want.entries[e].point) << e;
    ASSERT_EQ(got.entries[e].alpha, want.entries[e].alpha) << e;
  }
  // Deterministic: a second build gives the same bytes.
  const PpfTable again = build_ppf_table(test_device(), cloud, q);
  EXPECT_EQ(again.offsets, got.offsets);
  EXPECT_EQ(0, std::memcmp(again.entries.data(), got.entries.data(),
                           got.entries.size() * sizeof(bp_ppf_entry)));
}

TEST(PpfTable, HoldsTheReferenceMultisetUpToBinEdges) {
  std::mt19937 rng(7);
  const bp_ppf_quant q = make_ppf_quant(60.0f, 20, 30);  // larger than the cloud: every pair
  const PointCloud cloud = random_cloud(rng, 500, 30.0f);
  const PpfTable got = build_ppf_table(test_device(), cloud, q);
  const PpfTable want = build_ppf_table_reference(cloud, q);
  ASSERT_EQ(got.entries.size(), 500u * 499u);  // no pair lost to a collision
  ASSERT_EQ(want.entries.size(), 500u * 499u);
  // (key, point, alpha bin) multisets: equal but for the few pairs next to a bin edge.
  auto triples = [&](const PpfTable& t) {
    std::vector<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> out;
    for (std::uint32_t k = 0; k + 1 < t.offsets.size(); ++k)
      for (std::uint32_t e = t.offsets[k]; e < t.offsets[k + 1]; ++e)
        out.emplace_back(k, t.entries[e].point, bp_ppf_alpha_bin(t.entries[e].alpha, q));
    std::sort(out.begin(), out.end());
    return out;
  };
  const auto a = triples(got), b = triples(want);
  std::vector<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> diff;
  std::set_symmetric_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(diff));
  EXPECT_LT(diff.size(), a.size() / 500) << diff.size();
  for (std::uint32_t k = 0; k + 1 < got.offsets.size(); ++k)
    for (std::uint32_t e = got.offsets[k] + 1; e < got.offsets[k + 1]; ++e)
      ASSERT_LE(got.entries[e - 1].point, got.entries[e].point);  // ordered by reference point
}

TEST(PpfTable, EmptyAndSinglePointClouds) {
  const bp_ppf_quant q = make_ppf_quant(10.0f, 20, 30);
  for (std::size_t n : {0u, 1u}) {
    PointCloud c;
    for (std::size_t i = 0; i < n; ++i) {
      c.points.emplace_back(1, 1, 1);
      c.normals.emplace_back(1, 0, 0);
    }
    const PpfTable t = build_ppf_table(test_device(), c, q);
    EXPECT_EQ(t.offsets.size(), bp_ppf_key_count(q) + 1);
    EXPECT_EQ(t.offsets.back(), 0u);
    EXPECT_TRUE(t.entries.empty());
    EXPECT_EQ(t.distinct_keys(), 0u);
  }
}

namespace {

PpfModel train_box() {
  return train_ppf_model(box_mesh({40, 30, 20}), PpfTrainParams{});
}

}  // namespace

TEST(PpfTrain, BoxModelHasEveryPairAndIsDeterministic) {
  PpfTrainStats stats;
  const PpfModel m = train_ppf_model(box_mesh({40, 30, 20}), PpfTrainParams{}, &stats);
  EXPECT_NEAR(m.diameter, std::sqrt(40.0f * 40 + 30 * 30 + 20 * 20), 1e-3f);
  EXPECT_FLOAT_EQ(m.voxel_size, 0.05f * m.diameter);
  const std::size_t n = m.cloud.points.size();
  // Surface 5200 mm^2 at a voxel of 2.69 mm: roughly one point per voxel face area.
  EXPECT_GT(n, 400u);
  EXPECT_LT(n, 1400u);
  EXPECT_EQ(stats.points, n);
  EXPECT_EQ(m.table.entries.size(), n * (n - 1));  // all within the diameter, none coincident
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_NEAR(m.cloud.normals[i].norm(), 1.0f, 1e-6f);
    const auto& p = m.cloud.points[i];
    EXPECT_TRUE(p.x() >= 0 && p.x() <= 40 && p.y() >= 0 && p.y() <= 30 && p.z() >= 0 && p.z() <= 20);
  }
  EXPECT_EQ(serialize_ppf_model(m), serialize_ppf_model(train_box()));
}

TEST(PpfTrain, BadParametersAndMeshesAreInputErrors) {
  const Mesh box = box_mesh({40, 30, 20});
  for (double r : {0.0, -0.05, std::nan(""), 1.5, 1e-6}) {
    PpfTrainParams p;
    p.voxel_ratio = r;
    EXPECT_THROW(train_ppf_model(box, p), InputError) << r;
  }
  for (std::uint32_t s : {0u, 1000000u}) {
    PpfTrainParams p;
    p.distance_steps = s;
    EXPECT_THROW(train_ppf_model(box, p), InputError);
    p = {};
    p.angle_steps = s;
    EXPECT_THROW(train_ppf_model(box, p), InputError);
  }
  EXPECT_THROW(train_ppf_model(Mesh{}, PpfTrainParams{}), InputError);
  Mesh flat = box;
  for (auto& t : flat.triangles) t = {0, 0, 1};  // no area
  EXPECT_THROW(train_ppf_model(flat, PpfTrainParams{}), InputError);
}

TEST(PpfModelFile, RoundTripAndRefusals) {
  const PpfModel m = train_box();
  const std::string bytes = serialize_ppf_model(m);
  const PpfModel back = parse_ppf_model(bytes, "box.ppfm");
  EXPECT_EQ(back.diameter, m.diameter);
  EXPECT_EQ(back.voxel_size, m.voxel_size);
  EXPECT_EQ(0, std::memcmp(&back.quant, &m.quant, sizeof m.quant));
  EXPECT_EQ(back.cloud.points, m.cloud.points);
  EXPECT_EQ(back.cloud.normals, m.cloud.normals);
  EXPECT_EQ(back.table.offsets, m.table.offsets);
  EXPECT_EQ(serialize_ppf_model(back), bytes);

  for (std::size_t len : {std::size_t(0), std::size_t(5), std::size_t(8), std::size_t(40),
                          std::size_t(80), std::size_t(100), bytes.size() / 2, bytes.size() - 1})
    EXPECT_NE(parse_message(bytes.substr(0, len)).find("model file x.ppfm is truncated"),
              std::string::npos)
        << len << ": " << parse_message(bytes.substr(0, len));
  std::string wrong = bytes;
  wrong[0] = 'X';
  EXPECT_NE(parse_message(wrong).find("not a binpick PPF model"), std::string::npos);
  wrong = bytes;
  wrong[8] = 8;  // version 8
  EXPECT_NE(parse_message(wrong).find(
                "was written by format version 8, this binpick reads versions 1 to 7: retrain"),
            std::string::npos)
      << parse_message(wrong);
  wrong = bytes;
  wrong[bytes.size() / 2] ^= 0x10;
  EXPECT_NE(parse_message(wrong).find("corrupt"), std::string::npos);
  EXPECT_NE(parse_message(bytes + "x").find("corrupt"), std::string::npos);

  const auto path = std::filesystem::temp_directory_path() / "binpick_test_box.ppfm";
  write_ppf_model(path, m);
  EXPECT_EQ(serialize_ppf_model(read_ppf_model(path)), bytes);
  std::filesystem::remove(path);
  EXPECT_THROW(read_ppf_model(path), InputError);  // missing file
}

TEST(PpfTrain, FindsTheSymmetriesOfThePart) {
  PpfTrainStats stats;
  const PpfModel m = train_ppf_model(box_mesh({40, 30, 20}), PpfTrainParams{}, &stats);
  // Three unequal sides: the half turns about the three axes through the centre.
  EXPECT_TRUE(m.symmetries.continuous.empty());
  ASSERT_EQ(m.symmetries.discrete.size(), 3u);
  for (const Eigen::Matrix4d& s : m.symmetries.discrete) {
    const Eigen::Matrix3d R = s.topLeftCorner<3, 3>();
    EXPECT_NEAR(R.trace(), -1.0, 1e-9);  // a half turn
    const Eigen::Vector3d centre(20, 15, 10);
    const Eigen::Vector3d t = s.topRightCorner<3, 1>();
    EXPECT_LT((R * centre + t - centre).norm(), 1e-6);
  }
  EXPECT_GE(stats.symmetry_s, 0.0);
}

TEST(PpfModelFile, SymmetriesRoundTripAndVersionOneIsStillRead) {
  PpfModel m = train_box();
  m.symmetries.continuous.push_back({{0, 0.6, 0.8}, {1.5, -2, 3}});
  const std::string bytes = serialize_ppf_model(m);
  const PpfModel back = parse_ppf_model(bytes, "box.ppfm");
  ASSERT_EQ(back.symmetries.continuous.size(), 1u);
  EXPECT_EQ(back.symmetries.continuous[0].axis, m.symmetries.continuous[0].axis);
  EXPECT_EQ(back.symmetries.continuous[0].offset, m.symmetries.continuous[0].offset);
  ASSERT_EQ(back.symmetries.discrete.size(), m.symmetries.discrete.size());
  for (std::size_t k = 0; k < m.symmetries.discrete.size(); ++k)
    EXPECT_EQ(back.symmetries.discrete[k], m.symmetries.discrete[k]);
  EXPECT_EQ(serialize_ppf_model(back), bytes);

  // A file of version 1 (before symmetries): the same model, without them.
  const std::string v1 = serialize_ppf_model(m, 1);
  EXPECT_EQ(v1[8], 1);
  const PpfModel old = parse_ppf_model(v1, "old.ppfm");
  EXPECT_TRUE(old.symmetries.empty());
  EXPECT_EQ(old.cloud.points, m.cloud.points);
  EXPECT_EQ(old.table.offsets, m.table.offsets);
  EXPECT_EQ(old.table.entries.size(), m.table.entries.size());
  PpfModel without = m;
  without.symmetries = {};
  without.fit_cloud = {};
  // Read from a file without look-alikes, they are found again on the points (with no exact
  // symmetries known, the box's half turns are look-alikes); there are no probes.
  without.lookalikes = find_lookalikes(m.cloud, m.voxel_size, {});
  without.lookalike_probes = {};
  without.probe_lookalike = {};
  without.edge_probes = {};
  without.edge_probe_rim = {};
  without.grasps = {};
  EXPECT_TRUE(serialize_ppf_model(old) == serialize_ppf_model(without));  // (no byte dump)
  EXPECT_THROW(serialize_ppf_model(m, 8), std::logic_error);
  EXPECT_THROW(serialize_ppf_model(m, 0), std::logic_error);

  // Cut inside the symmetries, or right after the table (no counts): truncated.
  EXPECT_NE(parse_message(bytes.substr(0, bytes.size() - 50)).find("is truncated"), std::string::npos);
  std::string relabelled = bytes;  // version 6 bytes called version 1: the symmetries are extra
  relabelled[8] = 1;
  EXPECT_NE(parse_message(relabelled).find("bytes after the end"), std::string::npos);
  // Not a rotation, a zero axis, an absurd count: corrupt.
  PpfModel bad = m;
  bad.symmetries.discrete[0](0, 0) = 2;
  EXPECT_NE(parse_message(serialize_ppf_model(bad)).find("is corrupt (symmetry)"), std::string::npos);
  bad = m;
  bad.symmetries.continuous[0].axis.setZero();
  EXPECT_NE(parse_message(serialize_ppf_model(bad)).find("is corrupt (symmetry)"), std::string::npos);
  std::string huge = serialize_ppf_model(without, 2);
  huge[huge.size() - 5] = 0x7f;  // the continuous count's high byte
  EXPECT_NE(parse_message(huge).find("is corrupt (symmetry count)"), std::string::npos) << parse_message(huge);
}

TEST(PpfModelFile, RefinementPointsRoundTripAndVersionTwoIsStillRead) {
  const PpfModel m = train_box();
  // Half the voxel: about four times the points, on the same surface.
  EXPECT_GT(m.fit_cloud.points.size(), 3 * m.cloud.points.size());
  EXPECT_LT(m.fit_cloud.points.size(), 5 * m.cloud.points.size());
  ASSERT_EQ(m.fit_cloud.normals.size(), m.fit_cloud.points.size());
  for (const auto& n : m.fit_cloud.normals) EXPECT_NEAR(n.norm(), 1.0f, 1e-5f);
  const std::string bytes = serialize_ppf_model(m);
  const PpfModel back = parse_ppf_model(bytes, "box.ppfm");
  EXPECT_EQ(back.fit_cloud.points, m.fit_cloud.points);
  EXPECT_EQ(back.fit_cloud.normals, m.fit_cloud.normals);

  const std::string v2 = serialize_ppf_model(m, 2);
  const PpfModel old = parse_ppf_model(v2, "old.ppfm");
  EXPECT_TRUE(old.fit_cloud.points.empty());
  EXPECT_EQ(old.cloud.points, m.cloud.points);
  EXPECT_EQ(old.symmetries.discrete.size(), m.symmetries.discrete.size());

  // A count beyond any model, or a cut inside the points: corrupt, truncated. (Version 4: the
  // points are followed by the look-alike and probe counts (8 bytes), both 0 for the box.)
  const std::string v4 = serialize_ppf_model(m, 4);
  std::string huge = v4;
  ASSERT_TRUE(m.lookalikes.empty());
  const std::size_t count_at = v4.size() - 8 - 24 * m.fit_cloud.points.size() - 4;
  huge[count_at + 3] = 0x7f;
  EXPECT_NE(parse_message(huge).find("is corrupt (fit point count)"), std::string::npos)
      << parse_message(huge);
  EXPECT_NE(parse_message(v4.substr(0, count_at + 2)).find("is truncated"), std::string::npos);
  PpfModel nan = m;
  nan.fit_cloud.points[3].x() = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(parse_message(serialize_ppf_model(nan)).find("is corrupt (fit point 3)"),
            std::string::npos);
}

TEST(SurfaceSampling, UniformOnTheSurfaceWithFaceNormals) {
  const Mesh box = box_mesh({10, 10, 10});
  const PointCloud a = sample_surface(box, 6000), b = sample_surface(box, 6000);
  EXPECT_EQ(a.points, b.points);
  int on_top = 0;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    const auto& p = a.points[i];
    const auto& n = a.normals[i];
    EXPECT_NEAR(n.norm(), 1.0f, 1e-6f);
    EXPECT_NEAR(std::fabs(n.x()) + std::fabs(n.y()) + std::fabs(n.z()), 1.0f, 1e-6f);  // axis
    if (n.z() > 0.5f) {
      ++on_top;
      EXPECT_NEAR(p.z(), 10.0f, 1e-4f);
    }
  }
  EXPECT_NEAR(on_top, 1000, 150);  // one face in six
  EXPECT_NEAR(surface_area(box), 600.0, 1e-9);
}
