// Patchy depth dropout (--dropout-share, --dropout-patch): the shader against the C++
// reference on random scenes, the share it takes on planes, the patches' size and spatial
// correlation, share 0 changing nothing, determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>

#include <fmt/format.h>

#include "host/runtime/vk/vk_context.hpp"
#include "synth/sensor/sensor_patches.hpp"
#include "synth/sensor/sensor_reference.hpp"
#include "synth/sensor/sensor_stage.hpp"

using namespace binpick;

namespace {
const bool validation_on = [] { return setenv("BINPICK_VK_VALIDATION", "1", 1) == 0; }();

RenderCamera camera(std::uint32_t w, std::uint32_t h, double f) {
  return {w, h, f, f, (w - 1) / 2.0, (h - 1) / 2.0, 100.0, 5000.0};
}

// Every pixel on the plane z = z0 + slope_x x (camera frame, mm), normal facing the camera.
SensorImages plane(const RenderCamera& c, double z0, double slope_x) {
  const std::size_t n = std::size_t(c.width) * c.height;
  SensorImages in{c.width, c.height, std::vector<float>(n), std::vector<float>(3 * n), std::vector<std::uint8_t>(n, 120)};
  for (std::uint32_t v = 0; v < c.height; ++v)
    for (std::uint32_t u = 0; u < c.width; ++u) {
      const std::size_t i = std::size_t(v) * c.width + u;
      const double rx = (u - c.cx) / c.fx;
      in.depth_mm[i] = float(z0 / (1 - slope_x * rx));  // the ray z (rx, ry, 1) meets the plane
      in.normals[3 * i] = float(slope_x), in.normals[3 * i + 2] = -1.0f;
    }
  return in;
}

// A floor with raised rectangles, every depth jittered by up to 1 mm (random points, so the
// field is met at random values), random gray, a few pixels without surface.
SensorImages random_scene(const RenderCamera& c, std::mt19937& rng) {
  SensorImages in = plane(c, 1000, 0);
  std::uniform_real_distribution<double> unit(0, 1), jitter(-0.5, 0.5);
  for (int k = 0; k < 8; ++k) {
    const double u0 = unit(rng) * c.width, v0 = unit(rng) * c.height, top = 700 + 250 * unit(rng);
    const double u1 = u0 + unit(rng) * c.width / 3, v1 = v0 + unit(rng) * c.height / 3;
    for (std::uint32_t v = 0; v < c.height; ++v)
      for (std::uint32_t u = 0; u < c.width; ++u)
        if (u >= u0 && u < u1 && v >= v0 && v < v1) in.depth_mm[std::size_t(v) * c.width + u] = float(top);
  }
  for (std::size_t i = 0; i < in.depth_mm.size(); ++i) {
    in.depth_mm[i] += float(jitter(rng));
    in.gray[i] = std::uint8_t(rng() % 256);
  }
  for (int k = 0; k < 5; ++k) in.depth_mm[rng() % in.depth_mm.size()] = 0.0f;
  return in;
}

// No other reason to lose depth on a plane: the dropped share is the patches' alone.
SensorModel patches_only(double share, double patch_mm) {
  SensorModel m;
  m.kind = SensorModel::Kind::structured_light;
  m.grazing_limit_deg = 90;
  m.edge_radius_px = 0;
  m.dropout_share = share;
  m.dropout_patch_mm = patch_mm;
  return m;
}

// The field at pixel i's (ideal) point, as the reference evaluates it.
float field_at(const SensorParams& p, const SensorImages& in, std::size_t i) {
  const std::uint32_t u = std::uint32_t(i % p.width), v = std::uint32_t(i / p.width);
  const float z = in.depth_mm[i];
  const float rx = (float(u) - p.cx) / p.fx, ry = (float(v) - p.cy) / p.fy;
  return patch_field(patch_key(p.seed_lo, p.seed_hi), p.patch_inv_mm, rx * z, ry * z, z);
}

double patch_share(const SensorOutput& out) {
  const DropoutCounts c = count_dropout(out.dropout);
  return double(c[Dropout::patch]) / double(c[Dropout::patch] + c[Dropout::valid]);
}

// Of the dropped pixels whose right neighbour has a surface, the share whose neighbour is
// dropped too; and the mean length of a row's runs of dropped pixels.
std::pair<double, double> right_neighbour_and_run(const SensorOutput& out, std::uint32_t w) {
  std::size_t pairs = 0, both = 0, runs = 0, dropped = 0;
  const auto patch = std::uint8_t(Dropout::patch);
  for (std::size_t i = 0; i < out.dropout.size(); ++i) {
    if (out.dropout[i] != patch) continue;
    ++dropped;
    const bool row_start = i % w == 0 || out.dropout[i - 1] != patch;
    runs += row_start;
    if ((i + 1) % w != 0) ++pairs, both += out.dropout[i + 1] == patch;
  }
  return {double(both) / double(std::max<std::size_t>(pairs, 1)), double(dropped) / double(std::max<std::size_t>(runs, 1))};
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), 4 * a.size()) == 0;
}

bool identical(const SensorOutput& a, const SensorOutput& b) {
  return same_bits(a.depth_mm, b.depth_mm) && same_bits(a.points, b.points) &&
         same_bits(a.normals, b.normals) && a.gray == b.gray && a.dropout == b.dropout;
}

}  // namespace

TEST(SensorModelPatches, MatchesReferenceOnRandomScenes) {
  ASSERT_TRUE(validation_on);
  std::mt19937 rng(21);
  std::size_t near_threshold = 0, compared = 0;
  for (auto [w, h] : {std::pair{1u, 1u}, {64u, 48u}, {200u, 150u}}) {
    const RenderCamera cam = camera(w, h, 1.2 * w);
    const SensorImages in = random_scene(cam, rng);
    SensorStage stage(vkrt::Context::shared(), w, h);
    for (auto [share, patch_mm] : {std::pair{0.3, 20.0}, {0.6, 5.0}, {0.9, 50.0}, {0.05, 1.0}}) {
      SensorModel m = patches_only(share, patch_mm);
      m.grazing_limit_deg = 75, m.edge_radius_px = 1, m.specular_cone_deg = 4;
      const SensorParams p = sensor_params(cam, m, rng());
      SCOPED_TRACE(fmt::format("{}x{} share {} patch {} mm", w, h, share, patch_mm));
      const SensorOutput got = stage.run(in, p);
      const SensorOutput want = sensor_model_reference(in, p);
      for (std::size_t i = 0; i < want.dropout.size(); ++i) {
        ASSERT_EQ(int(got.gray[i]), int(want.gray[i])) << i;
        ++compared;
        if (got.dropout[i] == want.dropout[i]) {
          ASSERT_EQ(got.depth_mm[i] > 0, want.depth_mm[i] > 0) << i;
          continue;
        }
        // Only a patch decision may differ, and only where the field is at the threshold.
        const auto patch = std::uint8_t(Dropout::patch), valid = std::uint8_t(Dropout::valid);
        ASSERT_TRUE((got.dropout[i] == patch && want.dropout[i] == valid) ||
                    (got.dropout[i] == valid && want.dropout[i] == patch)) << i;
        ASSERT_LT(std::fabs(field_at(p, in, i) - p.patch_threshold), 1e-5f) << i;
        ++near_threshold;
      }
      if (w >= 64) {
        const DropoutCounts c = count_dropout(got.dropout);
        EXPECT_GT(c[Dropout::patch], 0u) << c.summary();
        EXPECT_GT(c[Dropout::edge], 0u) << c.summary();  // the patches come after the other reasons
      }
    }
  }
  std::printf("[ patches  ] %zu of %zu pixels decided differently by device and reference\n",
              near_threshold, compared);
  EXPECT_LE(near_threshold, compared / 10000 + 1);
}

// On planes the patches take the share asked for. The threshold comes from the field's
// distribution over space; a view sees a finite number of patches, so the share it gets
// scatters about that: with about 7500 patches in view (2000 x 1500 mm at 20 mm), within 0.015.
TEST(SensorModelPatches, DroppedShareIsTheShareAskedFor) {
  const RenderCamera cam = camera(400, 300, 200);  // 5 mm pixels at 1 m
  double worst = 0;
  for (auto [z0, slope] : {std::pair{1000.0, 0.0}, {1237.0, 0.0}, {1000.0, 0.4}}) {
    const SensorImages in = plane(cam, z0, slope);
    for (double share : {0.1, 0.3, 0.5, 0.7, 0.9, 0.95}) {
      for (std::uint64_t seed : {1u, 2u, 3u}) {
        const SensorModel m = patches_only(share, 20);
        const double got = patch_share(sensor_model(in, sensor_params(cam, m, seed)));
        worst = std::max(worst, std::fabs(got - share));
        EXPECT_NEAR(got, share, 0.015) << "plane z " << z0 << " slope " << slope << " seed " << seed;
      }
    }
  }
  std::printf("[ patches  ] largest |dropped share - asked| on planes: %.4f\n", worst);
}

// The threshold itself, over points spread through space (as the table is made, but other
// points and other seeds): the share below it is the share asked for, to 0.003.
TEST(SensorModelPatches, ThresholdGivesTheShareOverSpace) {
  EXPECT_EQ(patch_threshold(0), -1.0f);
  float last = -1;
  for (double share : {0.05, 0.2, 0.5, 0.8, 0.95}) {
    const float t = patch_threshold(share);
    EXPECT_GT(t, last);
    last = t;
    for (std::uint32_t seed : {7u, 8u}) {
      std::mt19937 rng(seed);
      std::uniform_real_distribution<float> pos(-3000, 3000);
      const std::uint32_t key = patch_key(seed, 99);
      const int n = 200000;
      int below = 0;
      for (int k = 0; k < n; ++k) below += patch_field(key, 1 / 20.0f, pos(rng), pos(rng), pos(rng)) < t;
      EXPECT_NEAR(double(below) / n, share, 0.004) << share;
    }
  }
}

// Patches, not pixels: a dropped pixel's right neighbour is dropped far more often than the
// share (independent dropout would give the share itself), and the runs of dropped pixels
// along a row scale with the patch size in mm, not in pixels.
TEST(SensorModelPatches, PatchesAreSpatiallyCorrelatedAndMetric) {
  const RenderCamera cam = camera(400, 300, 400);  // 2.5 mm pixels at 1 m
  const SensorImages near_plane = plane(cam, 1000, 0), far_plane = plane(cam, 2000, 0);
  auto measure = [&](const SensorImages& in, double patch_mm) {
    return right_neighbour_and_run(sensor_model(in, sensor_params(cam, patches_only(0.5, patch_mm), 4)), cam.width);
  };
  const auto [neighbour, run20] = measure(near_plane, 20);
  const auto [neighbour40, run40] = measure(near_plane, 40);
  const auto [neighbour_far, run20_far] = measure(far_plane, 20);
  std::printf("[ patches  ] share 0.5: right neighbour dropped %.3f; mean run %.1f px at 20 mm, "
              "%.1f px at 40 mm, %.1f px at 20 mm twice as far\n", neighbour, run20, run40, run20_far);
  EXPECT_GT(neighbour, 0.85);
  EXPECT_GT(neighbour40, neighbour);
  EXPECT_GT(neighbour_far, 0.7);
  EXPECT_NEAR(run40 / run20, 2.0, 0.4);      // twice the patch: twice the run
  EXPECT_NEAR(run20 / run20_far, 2.0, 0.4);  // twice as far: half the pixels
}

// Share 0 is the model as it was: the same parameters, the same images bit for bit, whatever
// the patch size; and the patches keep the gray image as rendered.
TEST(SensorModelPatches, ShareZeroChangesNothing) {
  std::mt19937 rng(22);
  const RenderCamera cam = camera(64, 48, 70);
  const SensorImages in = random_scene(cam, rng);
  SensorModel before;
  before.kind = SensorModel::Kind::structured_light;
  SensorModel off = before;
  off.dropout_patch_mm = 55;
  const SensorParams a = sensor_params(cam, before, 5), b = sensor_params(cam, off, 5);
  EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0);
  EXPECT_EQ(a.flags & kSensorPatches, 0u);
  EXPECT_TRUE(identical(sensor_model(in, a), sensor_model(in, b)));
  EXPECT_EQ(count_dropout(sensor_model(in, a).dropout)[Dropout::patch], 0u);

  SensorModel on = before;
  on.dropout_share = 0.5;
  const SensorOutput with = sensor_model(in, sensor_params(cam, on, 5));
  const SensorOutput without = sensor_model(in, a);
  EXPECT_EQ(with.gray, without.gray);
  std::size_t changed = 0;
  for (std::size_t i = 0; i < with.dropout.size(); ++i) {
    if (with.dropout[i] == without.dropout[i]) {
      ASSERT_EQ(with.depth_mm[i], without.depth_mm[i]) << i;  // the noise is drawn as before
      continue;
    }
    ++changed;
    ASSERT_EQ(without.dropout[i], std::uint8_t(Dropout::valid)) << i;
    ASSERT_EQ(with.dropout[i], std::uint8_t(Dropout::patch)) << i;
    ASSERT_EQ(with.depth_mm[i], 0.0f);
    ASSERT_EQ(with.points[3 * i + 2], 0.0f);
  }
  EXPECT_GT(changed, 0u);
}

TEST(SensorModelPatches, SameSeedSamePatches) {
  std::mt19937 rng(23);
  const RenderCamera cam = camera(64, 48, 70);
  const SensorImages in = random_scene(cam, rng);
  SensorModel m;
  m.kind = SensorModel::Kind::structured_light;
  m.dropout_share = 0.6, m.dropout_patch_mm = 10;
  const SensorOutput a = sensor_model(in, sensor_params(cam, m, 77));
  const SensorOutput b = sensor_model(in, sensor_params(cam, m, 77));
  const SensorOutput c = sensor_model(in, sensor_params(cam, m, 78));
  EXPECT_TRUE(identical(a, b));
  EXPECT_NE(a.dropout, c.dropout);  // the patches lie elsewhere under another seed
}
