// The structured-light sensor model's shaders (sensor_projector.comp, sensor_measure.comp)
// against their C++ reference on random scenes of boxes on a floor, with the validation layer
// on; degenerate images; the ideal sensor; determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>

#include "host/runtime/vk/vk_context.hpp"
#include "synth/sensor/sensor_apply.hpp"
#include "synth/sensor/sensor_reference.hpp"
#include "synth/sensor/sensor_stage.hpp"

using namespace binpick;

namespace {
const bool validation_on = [] { return setenv("BINPICK_VK_VALIDATION", "1", 1) == 0; }();

RenderCamera small_camera(std::uint32_t w, std::uint32_t h, double f) {
  return {w, h, f, f, (w - 1) / 2.0, (h - 1) / 2.0, 100.0, 5000.0};
}

// Axis-aligned boxes standing on a floor at floor_z, ray cast from the camera: depth and the
// normal (facing the camera) of the nearest surface.
struct Box { double x0, x1, y0, y1, top; };

SensorImages box_scene(const RenderCamera& c, double floor_z, const std::vector<Box>& boxes) {
  const std::size_t n = std::size_t(c.width) * c.height;
  SensorImages in{c.width, c.height, std::vector<float>(n), std::vector<float>(3 * n), std::vector<std::uint8_t>(n)};
  for (std::uint32_t v = 0; v < c.height; ++v)
    for (std::uint32_t u = 0; u < c.width; ++u) {
      const double d[3] = {(u - c.cx) / c.fx, (v - c.cy) / c.fy, 1.0};
      double best = floor_z;
      double normal[3] = {0, 0, -1};
      for (const Box& b : boxes) {
        const double lo[3] = {b.x0, b.y0, b.top}, hi[3] = {b.x1, b.y1, floor_z};
        double t0 = 0, t1 = 1e30;
        int axis = -1;
        for (int k = 0; k < 3; ++k) {
          double a = lo[k] / d[k], e = hi[k] / d[k];
          if (d[k] == 0) {
            if (lo[k] > 0 || hi[k] < 0) t0 = 1e30;
            continue;
          }
          if (a > e) std::swap(a, e);
          if (a > t0) t0 = a, axis = k;
          t1 = std::min(t1, e);
        }
        if (t0 <= t1 && axis >= 0 && t0 < best) {
          best = t0;
          normal[0] = normal[1] = normal[2] = 0;
          normal[axis] = d[axis] > 0 ? -1 : 1;
        }
      }
      const std::size_t i = std::size_t(v) * c.width + u;
      in.depth_mm[i] = float(best);  // t is z: the ray's z component is 1
      for (int k = 0; k < 3; ++k) in.normals[3 * i + k] = float(normal[k]);
      in.gray[i] = std::uint8_t(51 + (u * 7 + v * 3) % 200);
    }
  return in;
}

SensorImages random_scene(const RenderCamera& c, std::mt19937& rng) {
  const double floor_z = 1000;
  std::uniform_real_distribution<double> pos(-0.6, 0.6), size(0.05, 0.3), top(600, 980);
  const double half_w = floor_z * c.width / (2 * c.fx), half_h = floor_z * c.height / (2 * c.fy);
  std::vector<Box> boxes;
  for (int k = 0; k < 12; ++k) {
    const double x = pos(rng) * half_w * 2, y = pos(rng) * half_h * 2;
    const double sx = size(rng) * half_w * 2, sy = size(rng) * half_h * 2;
    boxes.push_back({x, x + sx, y, y + sy, top(rng)});
  }
  SensorImages in = box_scene(c, floor_z, boxes);
  // Degenerate pixels and tilted normals (the model takes the normals as given).
  std::uniform_int_distribution<std::size_t> pixel(0, in.depth_mm.size() - 1);
  std::uniform_real_distribution<float> n11(-1, 1);
  for (int k = 0; k < 20; ++k) {
    const std::size_t i = pixel(rng);
    for (int j = 0; j < 3; ++j) in.normals[3 * i + j] = n11(rng);
  }
  const float bad[] = {0.0f, -5.0f, NAN, INFINITY, 250.0f, 4000.0f};  // last two: out of range
  for (float b : bad) in.depth_mm[pixel(rng)] = b;
  const std::size_t i = pixel(rng);
  in.normals[3 * i] = in.normals[3 * i + 1] = in.normals[3 * i + 2] = 0.0f;
  in.normals[3 * pixel(rng) + 1] = NAN;
  return in;
}

SensorModel structured(double baseline, double scale) {
  SensorModel m;
  m.kind = SensorModel::Kind::structured_light;
  m.specular_cone_deg = 6;
  m.baseline_mm = baseline;
  m.projector_scale = scale;
  m.noise_a_mm = 0.3, m.noise_b_per_mm = 5e-7, m.added_sigma_mm = 0.5;
  m.min_range_mm = 300, m.max_range_mm = 3000;
  return m;
}

// Dropout and gray exactly; depth to the device's log/cos precision (1e-5 of sigma) except
// where that moves a value across a rounding boundary of the quantisation: then exactly one
// step apart, at a few pixels.
void expect_same(const SensorOutput& got, const SensorOutput& want, double step_at_3m) {
  ASSERT_EQ(got.depth_mm.size(), want.depth_mm.size());
  std::size_t one_step = 0;
  for (std::size_t i = 0; i < want.depth_mm.size(); ++i) {
    ASSERT_EQ(int(got.dropout[i]), int(want.dropout[i])) << "pixel " << i;
    ASSERT_EQ(int(got.gray[i]), int(want.gray[i])) << i;
    const float d = std::fabs(got.depth_mm[i] - want.depth_mm[i]);
    if (d > 1e-4f + 4e-7f * want.depth_mm[i]) {
      ASSERT_LE(d, step_at_3m) << i;
      ++one_step;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      ASSERT_NEAR(got.points[3 * i + k], want.points[3 * i + k], 2e-4f + 1e-6f * want.depth_mm[i]) << i;
      ASSERT_EQ(std::memcmp(&got.normals[3 * i + k], &want.normals[3 * i + k], sizeof(float)), 0) << i;
    }
  }
  EXPECT_LE(one_step, want.depth_mm.size() / 500 + 1);
}

RenderedBin rendered_bin(const SensorImages& in) {
  RenderedBin bin;
  bin.width = in.width, bin.height = in.height;
  bin.depth_mm = in.depth_mm, bin.gray = in.gray, bin.normals = in.normals;
  return bin;
}

bool finite(const std::vector<float>& v) {
  return std::all_of(v.begin(), v.end(), [](float x) { return std::isfinite(x); });
}
}  // namespace

TEST(SensorModel, MatchesReferenceOnRandomScenes) {
  ASSERT_TRUE(validation_on);
  std::mt19937 rng(11);
  for (auto [w, h] : {std::pair{1u, 1u}, {64u, 48u}, {200u, 150u}}) {
    const RenderCamera cam = small_camera(w, h, 1.2 * w);
    const SensorImages in = random_scene(cam, rng);
    for (auto [baseline, scale, quant, ref] :
         {std::tuple{350.0, 0.5, 0.05, 1000.0}, {-200.0, 1.0, 0.5, 0.0}, {600.0, 0.25, 0.0, 0.0}}) {
      SensorModel m = structured(baseline, scale);
      m.quantisation_mm = quant, m.quantisation_ref_mm = ref;
      const SensorParams p = sensor_params(cam, m, 0x1234567890abcdefull);
      SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + " baseline " + std::to_string(baseline));
      SensorStage stage(vkrt::Context::shared(), w, h);
      const SensorOutput got = stage.run(in, p);
      const std::vector<float> raster = projector_raster_reference(in, p);
      const std::vector<float> device_raster = stage.raster();
      ASSERT_EQ(device_raster.size(), raster.size());
      for (std::size_t k = 0; k < raster.size(); ++k) ASSERT_EQ(device_raster[k], raster[k]) << "cell " << k;
      const SensorOutput want = sensor_measure_reference(in, raster, p);
      const double step_at_3m = ref > 0 ? quant * 9 : quant;
      expect_same(got, want, step_at_3m);
      EXPECT_TRUE(finite(got.depth_mm) && finite(got.points) && finite(got.normals));
      if (w > 1) {  // a scene with boxes loses depth for each reason
        const DropoutCounts c = count_dropout(got.dropout);
        EXPECT_GT(c[Dropout::valid], c.surface() / 3) << c.summary();
        for (Dropout d : {Dropout::shadow, Dropout::edge, Dropout::out_of_range, Dropout::no_surface})
          EXPECT_GT(c[d], 0u) << dropout_name(d) << ": " << c.summary();
        if (w >= 64) {
          EXPECT_GT(c[Dropout::grazing], 0u) << c.summary();
          EXPECT_GT(c[Dropout::specular], 0u) << c.summary();
        }
      }
    }
  }
}

TEST(SensorModel, EmptyAndSinglePixelImages) {
  const RenderCamera cam = small_camera(5, 5, 6);
  SensorModel m = structured(350, 0.5);
  const SensorParams p = sensor_params(cam, m, 1);
  SensorImages empty{5, 5, std::vector<float>(25, 0.0f), std::vector<float>(75, 0.0f), std::vector<std::uint8_t>(25, 0)};
  empty.depth_mm[3] = NAN, empty.depth_mm[7] = -1.0f, empty.depth_mm[9] = INFINITY;
  for (const SensorOutput& out : {sensor_model(empty, p), sensor_model_reference(empty, p)}) {
    EXPECT_EQ(count_dropout(out.dropout)[Dropout::no_surface], 25u);
    EXPECT_TRUE(std::all_of(out.depth_mm.begin(), out.depth_mm.end(), [](float z) { return z == 0.0f; }));
    EXPECT_TRUE(finite(out.points) && finite(out.normals));
  }
  // One surface pixel among empty ones: an edge (its neighbours have no surface), unless the
  // edge rule is off; alone in a 1 x 1 image it has no neighbour and keeps its depth.
  SensorImages one = empty;
  one.depth_mm.assign(25, 0.0f);
  one.depth_mm[12] = 1000.0f;
  one.normals[3 * 12 + 2] = -1.0f;
  one.gray[12] = 200;
  EXPECT_EQ(sensor_model(one, p).dropout[12], std::uint8_t(Dropout::edge));
  m.edge_radius_px = 0;
  const SensorParams no_edges = sensor_params(cam, m, 1);
  const SensorOutput kept = sensor_model(one, no_edges);
  EXPECT_EQ(kept.dropout[12], std::uint8_t(Dropout::valid));
  EXPECT_NEAR(kept.depth_mm[12], 1000.0f, 5.0f);
  EXPECT_EQ(kept.gray[12], 200);
  const RenderCamera single = small_camera(1, 1, 2);
  SensorImages pixel{1, 1, {1200.0f}, {0.0f, 0.0f, -1.0f}, {90}};
  const SensorOutput alone = sensor_model(pixel, sensor_params(single, structured(350, 0.5), 3));
  EXPECT_EQ(alone.dropout[0], std::uint8_t(Dropout::valid));
  EXPECT_NEAR(alone.depth_mm[0], 1200.0f, 5.0f);
}

TEST(SensorModel, IdealLeavesDepthUntouched) {
  std::mt19937 rng(12);
  const RenderCamera cam = small_camera(64, 48, 70);
  const SensorImages in = random_scene(cam, rng);
  SensorModel m;  // ideal
  const SensorParams p = sensor_params(cam, m, 5);
  const SensorOutput out = sensor_model(in, p);
  for (std::size_t i = 0; i < in.depth_mm.size(); ++i) {
    const float z = in.depth_mm[i];
    const bool surface = z > 0 && std::isfinite(z);
    const float want = surface ? z : 0.0f;
    ASSERT_EQ(std::memcmp(&out.depth_mm[i], &want, sizeof(float)), 0) << i;
    ASSERT_EQ(out.gray[i], in.gray[i]) << i;
    for (int k = 0; k < 3 && surface; ++k)
      ASSERT_EQ(std::memcmp(&out.normals[3 * i + k], &in.normals[3 * i + k], sizeof(float)), 0) << i;
  }
  expect_same(out, sensor_model_reference(in, p), 0);

  // On a rendered bin the ideal kind changes nothing at all.
  RenderedBin bin = rendered_bin(in);
  bin.points.assign(3 * in.depth_mm.size(), 1.5f);
  const RenderedBin before = bin;
  apply_sensor_model(vkrt::Context::shared(), cam, m, 5, bin);
  EXPECT_EQ(std::memcmp(bin.depth_mm.data(), before.depth_mm.data(), 4 * bin.depth_mm.size()), 0);
  EXPECT_EQ(std::memcmp(bin.points.data(), before.points.data(), 4 * bin.points.size()), 0);
  EXPECT_EQ(bin.gray, before.gray);
}

TEST(SensorModel, SameSeedSameOutput) {
  std::mt19937 rng(13);
  const RenderCamera cam = small_camera(64, 48, 70);
  const SensorImages in = random_scene(cam, rng);
  const SensorModel m = structured(350, 0.5);
  const SensorOutput a = sensor_model(in, sensor_params(cam, m, 77));
  const SensorOutput b = sensor_model(in, sensor_params(cam, m, 77));
  const SensorOutput c = sensor_model(in, sensor_params(cam, m, 78));
  EXPECT_EQ(std::memcmp(a.depth_mm.data(), b.depth_mm.data(), 4 * a.depth_mm.size()), 0);
  EXPECT_EQ(std::memcmp(a.points.data(), b.points.data(), 4 * a.points.size()), 0);
  EXPECT_EQ(a.dropout, b.dropout);
  EXPECT_EQ(a.dropout, c.dropout);  // the geometry does not depend on the seed
  EXPECT_NE(std::memcmp(a.depth_mm.data(), c.depth_mm.data(), 4 * a.depth_mm.size()), 0);
}

TEST(SensorModel, AppliesToARenderedBin) {
  std::mt19937 rng(14);
  const RenderCamera cam = small_camera(64, 48, 70);
  const SensorImages in = random_scene(cam, rng);
  const std::size_t n = in.depth_mm.size();
  RenderedBin bin = rendered_bin(in);
  bin.points.assign(3 * n, 0.0f);
  bin.instance.assign(n, -1);
  bin.px_visible = {0, 0};
  for (std::size_t i = 0; i < n; ++i)
    if (in.depth_mm[i] > 0 && in.depth_mm[i] < 990) bin.instance[i] = int(i % 2), ++bin.px_visible[i % 2];
  RenderedBin reference = bin;
  const SensorModel m = structured(350, 0.5);
  const DropoutCounts counts = apply_sensor_model(vkrt::Context::shared(), cam, m, 9, bin);
  apply_sensor_model_reference(cam, m, 9, reference);
  RenderedBin again = rendered_bin(in);  // through a stage kept for several bins
  SensorStage stage(vkrt::Context::shared(), cam.width, cam.height);
  for (int k = 0; k < 2; ++k) {
    again = rendered_bin(in);
    apply_sensor_model(stage, cam, m, 9, again);
  }
  EXPECT_EQ(std::memcmp(again.depth_mm.data(), bin.depth_mm.data(), 4 * n), 0);
  EXPECT_EQ(counts.surface() + counts[Dropout::no_surface], n);
  std::size_t with_depth = 0;
  for (std::size_t i = 0; i < n; ++i) {
    with_depth += bin.depth_mm[i] > 0;
    ASSERT_EQ(bin.depth_mm[i] > 0, reference.depth_mm[i] > 0) << i;
    if (bin.depth_mm[i] > 0) {
      ASSERT_NEAR(bin.points[3 * i + 2], bin.depth_mm[i], 1e-6f * bin.depth_mm[i]);
    }
  }
  EXPECT_EQ(with_depth, counts[Dropout::valid]);
  const auto valid = valid_pixels_per_part(bin);
  ASSERT_EQ(valid.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    EXPECT_GT(valid[k], 0u);
    EXPECT_LT(valid[k], bin.px_visible[k]);  // some of each part's pixels lost their depth
  }
}
