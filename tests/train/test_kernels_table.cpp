// The four kernels of the PPF hash table build (kernels/ppf_table.cl), each launched by itself
// and compared with a plain C++ reference of that one step (tests/support/kernel_refs.hpp).
//
// ppf_count and ppf_scatter compute the pair features themselves (bp_ppf_pair8). Their outputs
// are compared exactly with the step's reference fed the device's own pair features (the
// ppf_pair_features kernel, the same bp_ppf_pair8 on the same buffers), and with the reference fed
// the Eigen features (ppf_pair_feature_reference) up to pairs whose feature lies next to a bin
// edge (kAngleEdgeEps = 1e-4 rad, kDistanceEdgeRel = 1e-5 of max_distance); alphas within 1e-4
// rad of the Eigen ones. ppf_bucket_totals and ppf_group_slots are integer: exact, on random
// counts. The composed table is tests/train/test_ppf_model.cpp's.
#include <gtest/gtest.h>

#include <random>
#include <tuple>

#include "host/core/cloud_input.hpp"
#include "host/train/device_scan.hpp"
#include "host/train/ppf_table.hpp"
#include "tests/support/kernel_refs.hpp"

using namespace binpick;
using namespace binpick::test;

namespace {

constexpr u32 kCanary = 0xdeadbeefu;
constexpr std::size_t kGuard = 8;

// Random points in a cube with unit normals, a planar grid with one normal (few, large buckets)
// and copies of earlier points (coincident pairs: no key).
PointCloud random_cloud(std::mt19937& rng, std::size_t n_random, int grid, std::size_t copies,
                        float extent) {
  std::uniform_real_distribution<float> u(-extent / 2, extent / 2), c(-1, 1);
  PointCloud cloud;
  for (std::size_t i = 0; i < n_random; ++i) {
    cloud.points.emplace_back(u(rng), u(rng), u(rng));
    cloud.normals.push_back(Eigen::Vector3f(c(rng), c(rng), c(rng)));
  }
  for (int i = 0; i < grid; ++i)
    for (int j = 0; j < grid; ++j) {
      cloud.points.emplace_back(float(i), float(j), extent / 4);
      cloud.normals.emplace_back(0, 0, 1);
    }
  for (std::size_t k = 0; k < copies && !cloud.points.empty(); ++k) {
    const std::size_t i = std::uniform_int_distribution<std::size_t>(0, cloud.points.size() - 1)(rng);
    cloud.points.push_back(cloud.points[i]);
    cloud.normals.push_back(Eigen::Vector3f(c(rng), c(rng), 1.0f));
  }
  return with_unit_normals(cloud);
}

// The cloud on the device, and its pair features computed there by ppf_pair_features.
struct DeviceCloud {
  PointCloud cloud;
  std::size_t n = 0;
  ocl::Buffer<cl_float4> points, normals;
  std::vector<u32> keys;      // n * n
  std::vector<float> alphas;  // n * n
};
DeviceCloud on_device(ocl::Device& dev, PointCloud cloud, const bp_ppf_quant& q) {
  DeviceCloud d;
  d.n = cloud.points.size();
  d.points = upload(dev, pack_float4(cloud.points));
  d.normals = upload(dev, pack_float4(cloud.normals));
  ocl::Buffer<u32> keys(dev, d.n * d.n);
  ocl::Buffer<float> alphas(dev, d.n * d.n);
  cl::Kernel k = dev.kernel("ppf_features.cl", "ppf_pair_features");
  ocl::launch(dev, k, d.n, d.points, d.normals, u32(d.n), q, keys, alphas);
  d.keys = keys.read(dev);
  d.alphas = alphas.read(dev);
  d.cloud = std::move(cloud);
  return d;
}

// The routine's split into groups of rows (host/train/ppf_table.cpp).
std::pair<u32, u32> routine_groups(std::size_t n, std::size_t n_keys) {
  const std::size_t groups = ppf_table_groups(
      n, n_keys, ocl::Device::shared().device().getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>());
  return {u32(groups), u32((n + groups - 1) / groups)};
}

std::vector<PairFeature> eigen_features(const PointCloud& c, const bp_ppf_quant& q) {
  const std::size_t n = c.points.size();
  std::vector<PairFeature> f(n * n);
  for (std::size_t r = 0; r < n; ++r)
    for (std::size_t i = 0; i < n; ++i)
      if (i != r)
        f[r * n + i] = ppf_pair_feature_reference(c.points[r], c.normals[r], c.points[i], c.normals[i], q);
  return f;
}

struct TableCase {
  std::size_t n_random;
  int grid;
  std::size_t copies;
  float extent, max_distance;
  u32 dist_steps, angle_steps;
};
// Paper discretisation; a coarse one whose key count (7 * 5^3 = 875) divides no work group;
// a max_distance below most pair distances (most pairs skipped).
const TableCase kTables[] = {{300, 10, 20, 50.0f, 45.0f, 20, 30},
                             {200, 5, 10, 30.0f, 60.0f, 7, 10},
                             {150, 0, 5, 50.0f, 8.0f, 20, 30}};

}  // namespace

TEST(PpfTableKernels, ppf_count_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("ppf_table.cl", "ppf_count");
  std::mt19937 rng(301);
  std::size_t uncertain_total = 0, pairs_total = 0;
  for (const TableCase& t : kTables) {
    const bp_ppf_quant q = make_ppf_quant(t.max_distance, t.dist_steps, t.angle_steps);
    const u32 n_keys = bp_ppf_key_count(q);
    const DeviceCloud d = on_device(dev, random_cloud(rng, t.n_random, t.grid, t.copies, t.extent), q);
    const std::vector<PairFeature> ef = eigen_features(d.cloud, q);
    const auto [routine_g, routine_rows] = routine_groups(d.n, n_keys);
    // The routine's groups, one group, and more groups than rows need (empty trailing groups).
    for (auto [groups, rows] : {std::pair{routine_g, routine_rows}, {1u, u32(d.n)},
                                {u32(d.n / 7 + 2), 7u}}) {
      ocl::Buffer<u32> counts =
          guarded_buffer(dev, std::vector<u32>(std::size_t(groups) * n_keys, 0u), kGuard, kCanary);
      ocl::launch(dev, k, groups, d.points, d.normals, u32(d.n), q, rows, n_keys, counts);
      std::vector<u32> got = counts.read(dev);
      for (std::size_t i = 0; i < kGuard; ++i) ASSERT_EQ(got[got.size() - kGuard + i], kCanary);
      got.resize(got.size() - kGuard);
      // Exactly the histogram of the device's pair features.
      ASSERT_EQ(got, ppf_count_reference(d.keys, d.n, rows, groups, n_keys)) << groups;
      // The histogram of the Eigen features, up to the pairs next to a bin edge: per group, every
      // bucket holds at least the pairs that are certainly there, and the surplus is at most the
      // group's uncertain pairs.
      for (u32 g = 0; g < groups; ++g) {
        const auto [begin, end] = group_rows(g, rows, d.n);
        std::vector<u32> certain(n_keys, 0);
        std::size_t uncertain = 0;
        for (std::size_t r = begin; r < end; ++r)
          for (std::size_t i = 0; i < d.n; ++i) {
            if (i == r) continue;
            const PairFeature& f = ef[r * d.n + i];
            if (ppf_feature_near_edge(f, q)) ++uncertain;
            else if (f.key != BP_PPF_NO_KEY) ++certain[f.key];
          }
        std::size_t surplus = 0;
        for (u32 key = 0; key < n_keys; ++key) {
          const u32 c = got[std::size_t(g) * n_keys + key];
          ASSERT_GE(c, certain[key]) << "group " << g << " key " << key;
          surplus += c - certain[key];
        }
        ASSERT_LE(surplus, uncertain) << "group " << g;
        if (groups == routine_g) uncertain_total += uncertain, pairs_total += (end - begin) * d.n;
      }
    }
  }
  EXPECT_LT(uncertain_total, pairs_total / 100) << uncertain_total << " of " << pairs_total;
  std::printf("pairs next to a bin edge: %zu of %zu\n", uncertain_total, pairs_total);
}

TEST(PpfTableKernels, ppf_bucket_totals_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("ppf_table.cl", "ppf_bucket_totals");
  std::mt19937 rng(302);
  for (auto [groups, n_keys] : {std::pair{1u, 1u}, {1u, 875u}, {3u, 875u}, {64u, 67500u}, {7u, 33u}}) {
    std::uniform_int_distribution<u32> v(0, 4);
    std::vector<u32> counts(std::size_t(groups) * n_keys);
    for (auto& c : counts) c = v(rng) == 0 ? v(rng) : 0u;  // mostly empty buckets
    ocl::Buffer<u32> counts_buf = upload(dev, counts);
    ocl::Buffer<u32> totals = guarded_buffer(dev, std::vector<u32>(n_keys, kCanary), kGuard, kCanary);
    ocl::launch(dev, k, n_keys, counts_buf, groups, n_keys, totals);
    std::vector<u32> want = ppf_bucket_totals_reference(counts, groups, n_keys);
    want.insert(want.end(), kGuard, kCanary);
    ASSERT_EQ(totals.read(dev), want) << groups << " " << n_keys;
  }
}

TEST(PpfTableKernels, ppf_group_slots_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("ppf_table.cl", "ppf_group_slots");
  std::mt19937 rng(303);
  for (auto [groups, n_keys] : {std::pair{1u, 1u}, {1u, 875u}, {3u, 875u}, {64u, 67500u}, {7u, 33u}}) {
    std::uniform_int_distribution<u32> v(0, 4);
    std::vector<u32> counts(std::size_t(groups) * n_keys);
    for (auto& c : counts) c = v(rng) == 0 ? v(rng) : 0u;
    const std::vector<u32> offsets =
        exclusive_scan_reference(ppf_bucket_totals_reference(counts, groups, n_keys));
    ocl::Buffer<u32> counts_buf = guarded_buffer(dev, counts, kGuard, kCanary);
    ocl::Buffer<u32> offsets_buf = upload(dev, offsets);
    ocl::launch(dev, k, n_keys, counts_buf, groups, n_keys, offsets_buf);
    std::vector<u32> want = ppf_group_slots_reference(counts, groups, n_keys, offsets);
    want.insert(want.end(), kGuard, kCanary);
    ASSERT_EQ(counts_buf.read(dev), want) << groups << " " << n_keys;
  }
}

TEST(PpfTableKernels, ppf_scatter_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("ppf_table.cl", "ppf_scatter");
  std::mt19937 rng(304);
  std::size_t at_edge = 0, entries_total = 0;
  for (const TableCase& t : kTables) {
    const bp_ppf_quant q = make_ppf_quant(t.max_distance, t.dist_steps, t.angle_steps);
    const u32 n_keys = bp_ppf_key_count(q);
    const DeviceCloud d = on_device(dev, random_cloud(rng, t.n_random, t.grid, t.copies, t.extent), q);
    const auto [routine_g, routine_rows] = routine_groups(d.n, n_keys);
    for (auto [groups, rows] : {std::pair{routine_g, routine_rows}, {1u, u32(d.n)},
                                {u32(d.n / 7 + 2), 7u}}) {
      // The slots the earlier steps give, from the device features' histogram.
      const std::vector<u32> counts = ppf_count_reference(d.keys, d.n, rows, groups, n_keys);
      const std::vector<u32> offsets =
          exclusive_scan_reference(ppf_bucket_totals_reference(counts, groups, n_keys));
      const std::vector<u32> slots = ppf_group_slots_reference(counts, groups, n_keys, offsets);
      const u32 total = offsets.back();
      ocl::Buffer<u32> slots_buf = guarded_buffer(dev, slots, kGuard, kCanary);
      ocl::Buffer<bp_ppf_entry> entries =
          guarded_buffer(dev, std::vector<bp_ppf_entry>(total, {kCanary, -1.0f}), kGuard, {kCanary, -1.0f});
      ocl::launch(dev, k, groups, d.points, d.normals, u32(d.n), q, rows, n_keys, slots_buf, entries);
      const PpfScatterResult want =
          ppf_scatter_reference(d.keys, d.alphas, d.n, rows, groups, n_keys, slots, total);
      const std::vector<bp_ppf_entry> got = entries.read(dev);
      for (std::size_t e = 0; e < total; ++e) {
        ASSERT_EQ(got[e].point, want.entries[e].point) << e;
        ASSERT_TRUE(same_bits(got[e].alpha, want.entries[e].alpha)) << e;
      }
      for (std::size_t e = total; e < got.size(); ++e) ASSERT_EQ(got[e].point, kCanary) << e;
      std::vector<u32> slots_after = want.slots_after;
      slots_after.insert(slots_after.end(), kGuard, kCanary);
      ASSERT_EQ(slots_buf.read(dev), slots_after);  // each group's end in each bucket
      if (groups != routine_g) continue;
      // Against the Eigen features: entry e of bucket `key` holds pair pair_of[e].
      for (u32 key = 0; key < n_keys; ++key)
        for (u32 e = offsets[key]; e < offsets[key + 1]; ++e) {
          const std::size_t r = want.pair_of[e] / d.n, i = want.pair_of[e] % d.n;
          const PairFeature f = ppf_pair_feature_reference(d.cloud.points[r], d.cloud.normals[r],
                                                           d.cloud.points[i], d.cloud.normals[i], q);
          ++entries_total;
          if (f.key != key) {
            ++at_edge;
            ASSERT_TRUE(ppf_key_difference_at_edge(key, f, q)) << r << " " << i;
          } else {
            ASSERT_LT(circular_distance(got[e].alpha, f.alpha), 1e-4f) << r << " " << i;
          }
        }
    }
  }
  EXPECT_GT(entries_total, 0u);
  EXPECT_LT(at_edge, entries_total / 200 + 1) << at_edge << " of " << entries_total;
  std::printf("entries whose Eigen key differs (at a bin edge): %zu of %zu\n", at_edge, entries_total);
}

// Degenerate clouds through the routine's sequence, each step checked: no points (count and
// scatter run no work item; totals and slots still cover every key), one point (only the pair
// with itself), all points coincident (every pair skipped), all farther apart than
// max_distance; and launches in work groups that divide neither the groups nor the keys.
TEST(PpfTableKernels, DegenerateCloudsAndPaddedWorkGroups) {
  auto& dev = ocl::Device::shared();
  cl::Kernel count = dev.kernel("ppf_table.cl", "ppf_count");
  cl::Kernel totals = dev.kernel("ppf_table.cl", "ppf_bucket_totals");
  cl::Kernel slots = dev.kernel("ppf_table.cl", "ppf_group_slots");
  cl::Kernel scatter = dev.kernel("ppf_table.cl", "ppf_scatter");
  const bp_ppf_quant q = make_ppf_quant(10.0f, 7, 10);  // 875 keys
  const u32 n_keys = bp_ppf_key_count(q);
  std::mt19937 rng(305);
  std::vector<PointCloud> clouds(5);
  clouds[1].points = {{1, 2, 3}};
  clouds[1].normals = {{0, 1, 0}};
  for (int i = 0; i < 9; ++i) clouds[2].points.emplace_back(4, 4, 4), clouds[2].normals.emplace_back(0, 0, 1);
  for (int i = 0; i < 9; ++i) clouds[3].points.emplace_back(20.0f * i, 0, 0), clouds[3].normals.emplace_back(0, 1, 0);
  clouds[4] = random_cloud(rng, 61, 0, 3, 12.0f);
  for (std::size_t c = 0; c < clouds.size(); ++c) {
    const DeviceCloud d = on_device(dev, clouds[c], q);
    const auto [groups, rows] = routine_groups(d.n, n_keys);
    const u32 n = u32(d.n);
    ocl::Buffer<u32> counts = guarded_buffer(dev, std::vector<u32>(std::size_t(groups) * n_keys, 0u), kGuard, kCanary);
    ocl::Buffer<u32> totals_buf = guarded_buffer(dev, std::vector<u32>(n_keys, kCanary), kGuard, kCanary);
    ocl::Buffer<u32> offsets(dev, n_keys + 1);
    ocl::launch_local(dev, count, n > 0 ? groups : 0, 16, d.points, d.normals, n, q, rows, n_keys, counts);
    std::vector<u32> want_counts = ppf_count_reference(d.keys, d.n, rows, groups, n_keys);
    std::vector<u32> got_counts = counts.read(dev);
    ASSERT_EQ(std::vector<u32>(got_counts.begin(), got_counts.end() - kGuard), want_counts) << c;
    ocl::launch_local(dev, totals, n_keys, 64, counts, groups, n_keys, totals_buf);
    std::vector<u32> want_totals = ppf_bucket_totals_reference(want_counts, groups, n_keys);
    std::vector<u32> got_totals = totals_buf.read(dev);
    ASSERT_EQ(std::vector<u32>(got_totals.begin(), got_totals.begin() + n_keys), want_totals) << c;
    for (std::size_t i = n_keys; i < got_totals.size(); ++i) ASSERT_EQ(got_totals[i], kCanary) << c;
    const u32 total = exclusive_scan(dev, totals_buf, n_keys, offsets);
    const std::vector<u32> want_offsets = exclusive_scan_reference(want_totals);
    ASSERT_EQ(offsets.read(dev), want_offsets) << c;
    ocl::launch_local(dev, slots, n_keys, 64, counts, groups, n_keys, offsets);
    const std::vector<u32> want_slots = ppf_group_slots_reference(want_counts, groups, n_keys, want_offsets);
    got_counts = counts.read(dev);
    ASSERT_EQ(std::vector<u32>(got_counts.begin(), got_counts.end() - kGuard), want_slots) << c;
    ocl::Buffer<bp_ppf_entry> entries =
        guarded_buffer(dev, std::vector<bp_ppf_entry>(total, {kCanary, -1.0f}), kGuard, {kCanary, -1.0f});
    ocl::launch_local(dev, scatter, n > 0 ? groups : 0, 16, d.points, d.normals, n, q, rows, n_keys, counts, entries);
    const PpfScatterResult want = ppf_scatter_reference(d.keys, d.alphas, d.n, rows, groups, n_keys, want_slots, total);
    const std::vector<bp_ppf_entry> got = entries.read(dev);
    for (std::size_t e = 0; e < got.size(); ++e) {
      ASSERT_EQ(got[e].point, e < total ? want.entries[e].point : kCanary) << c << " " << e;
      if (e < total) {
        ASSERT_TRUE(same_bits(got[e].alpha, want.entries[e].alpha)) << c << " " << e;
      }
    }
    if (c < 4) {
      EXPECT_EQ(total, 0u) << c;  // none of the first four clouds has a pair
    } else {
      EXPECT_GT(total, 0u);
    }
  }
}
