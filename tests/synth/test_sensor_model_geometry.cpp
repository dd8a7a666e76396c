// The structured-light sensor model against geometry worked out by hand: the width of the
// shadow behind a step, grazing angles on tilted planes, the noise's growth with z^2 and the
// quantisation lattice. Runs the shaders (the reference agrees: test_sensor_model.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "synth/sensor/sensor_stage.hpp"

using namespace binpick;

namespace {

SensorModel plain_structured_light() {
  SensorModel m;
  m.kind = SensorModel::Kind::structured_light;
  m.grazing_limit_deg = 90;
  m.edge_radius_px = 0;
  m.noise_a_mm = m.noise_b_per_mm = 0;
  m.quantisation_mm = 0;
  m.min_range_mm = 100, m.max_range_mm = 100000;
  return m;
}

SensorImages flat_images(std::uint32_t w, std::uint32_t h) {
  const std::size_t n = std::size_t(w) * h;
  SensorImages in{w, h, std::vector<float>(n), std::vector<float>(3 * n, 0.0f), std::vector<std::uint8_t>(n, 128)};
  for (std::size_t i = 0; i < n; ++i) in.normals[3 * i + 2] = -1.0f;
  return in;
}

// Sample mean and standard deviation of measured - true depth over the pixels with depth.
std::pair<double, double> residual_stats(const SensorOutput& out, double z) {
  double sum = 0, sum2 = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < out.depth_mm.size(); ++i) {
    if (out.dropout[i] != std::uint8_t(Dropout::valid)) continue;
    const double r = out.depth_mm[i] - z;
    sum += r, sum2 += r * r, ++n;
  }
  const double mean = sum / double(n);
  return {mean, std::sqrt(sum2 / double(n) - mean * mean)};
}

}  // namespace

// A step seen from above, its edge on the optical axis (so the camera sees its wall edge-on):
// the top at z1 for x > 0, the floor at z2 for x < 0. The projector at (b, 0, 0), b > 0, sees
// past the edge onto the floor only beyond X_p = b (1 - z2 / z1): the floor pixels whose
// centres lie in [cx + f X_p / z2, cx), f b (1/z1 - 1/z2) pixels wide, are in shadow.
TEST(SensorModelGeometry, StepEdgeShadowHasTheWidthTriangulationPredicts) {
  const std::uint32_t w = 160, h = 24;
  const double f = 100, cx = (w - 1) / 2.0;  // pixel u's centre is at x = (u - cx) z / f
  const RenderCamera cam{w, h, f, f, cx, (h - 1) / 2.0, 100, 5000};
  for (auto [z1, z2, b] : {std::tuple{800.0, 1000.0, 300.0}, {900.0, 1000.0, 300.0},
                           {700.0, 1200.0, 150.0}, {800.0, 1000.0, -300.0}}) {
    SensorImages in = flat_images(w, h);
    for (std::uint32_t v = 0; v < h; ++v)
      for (std::uint32_t u = 0; u < w; ++u) in.depth_mm[v * w + u] = float(u > cx ? z1 : z2);
    int expected = 0;  // floor pixel centres inside the analytic shadow
    const double xp = b * (1 - z2 / z1);
    for (std::uint32_t u = 0; u < w; ++u)
      if (u < cx && b > 0 && (u - cx) * z2 / f >= xp) ++expected;
    const double width = b > 0 ? f * b * (1 / z1 - 1 / z2) : 0;
    EXPECT_NEAR(expected, width, 1.0);
    for (double scale : {1.0, 0.5}) {
      SensorModel m = plain_structured_light();
      m.baseline_mm = b, m.projector_scale = scale;
      const SensorOutput out = sensor_model(in, sensor_params(cam, m, 0));
      SCOPED_TRACE(testing::Message() << "z1 " << z1 << " z2 " << z2 << " b " << b << " scale " << scale);
      for (std::uint32_t v = 0; v < h; ++v) {
        int shadowed = 0, first = int(w), last = -1;
        for (std::uint32_t u = 0; u < w; ++u)
          if (out.dropout[v * w + u] == std::uint8_t(Dropout::shadow)) {
            ++shadowed, first = std::min(first, int(u)), last = std::max(last, int(u));
            ASSERT_LT(u, cx) << "only the floor is in shadow";
            ASSERT_EQ(out.gray[v * w + u], kShadowGray);
          } else {
            ASSERT_EQ(out.dropout[v * w + u], std::uint8_t(Dropout::valid)) << u;
            ASSERT_EQ(out.gray[v * w + u], 128);
          }
        // One projector cell is 1 / scale pixels wide: the shadow's far end is that exact.
        EXPECT_NEAR(shadowed, expected, 1 / scale) << "row " << v;
        if (shadowed > 0) {
          EXPECT_EQ(last - first + 1, shadowed) << "one band";
          EXPECT_EQ(last, int(std::floor(cx))) << "the band ends at the step";
        }
      }
    }
  }
}

// A plane through (0, 0, 1000) whose normal is tilted by theta from the optical axis about
// the x axis: the angle to each pixel's camera ray and projector ray is known exactly.
TEST(SensorModelGeometry, GrazingAnglesLoseDepth) {
  const std::uint32_t w = 64, h = 48;
  const double f = 200, z0 = 1000, b = 300;
  const RenderCamera cam{w, h, f, f, (w - 1) / 2.0, (h - 1) / 2.0, 100, 5000};
  for (double theta_deg : {60.0, 70.0, 80.0}) {
    const double t = theta_deg * M_PI / 180;
    const double n[3] = {0, std::sin(t), -std::cos(t)};
    SensorImages in = flat_images(w, h);
    std::vector<int> expected(w * h);  // 1 grazing, 0 kept, -1 within 0.05 degrees of the limit
    for (std::uint32_t v = 0; v < h; ++v)
      for (std::uint32_t u = 0; u < w; ++u) {
        const double d[3] = {(u - cam.cx) / f, (v - cam.cy) / f, 1};
        const double z = -std::cos(t) * z0 / (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]);
        const double p[3] = {d[0] * z, d[1] * z, z}, to_p[3] = {b - p[0], -p[1], -p[2]};
        const double cos_c = -(n[0] * p[0] + n[1] * p[1] + n[2] * p[2]) / std::hypot(p[0], p[1], p[2]);
        const double cos_p = (n[0] * to_p[0] + n[1] * to_p[1] + n[2] * to_p[2]) / std::hypot(to_p[0], to_p[1], to_p[2]);
        const double angle = std::acos(std::min(cos_c, cos_p)) * 180 / M_PI;
        const std::size_t i = v * w + u;
        in.depth_mm[i] = float(z);
        for (int k = 0; k < 3; ++k) in.normals[3 * i + k] = float(n[k]);
        expected[i] = std::fabs(angle - 75) < 0.05 ? -1 : angle > 75 ? 1 : 0;
      }
    SensorModel m = plain_structured_light();
    m.baseline_mm = b, m.grazing_limit_deg = 75;
    const SensorOutput out = sensor_model(in, sensor_params(cam, m, 0));
    std::size_t dropped = 0;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      ASSERT_NE(out.dropout[i], std::uint8_t(Dropout::shadow)) << "a plane casts no shadow on itself, " << i;
      if (expected[i] < 0) continue;
      ASSERT_EQ(out.dropout[i], std::uint8_t(expected[i] ? Dropout::grazing : Dropout::valid))
          << "theta " << theta_deg << " pixel " << i;
      dropped += expected[i];
    }
    if (theta_deg == 60) {
      EXPECT_EQ(dropped, 0u);
    } else if (theta_deg == 70) {
      EXPECT_GT(dropped, 0u);
      EXPECT_LT(dropped, expected.size());
    } else {
      EXPECT_GT(dropped, expected.size() * 3 / 4);  // the view spans 80 +- 6.7 degrees
    }
  }
}

// A plane facing the camera: the projector's mirror reflection reaches the camera where the
// normal is within the cone of the bisector of the rays to camera and projector, a patch
// around the point midway between them (x = b / 2), right of the image centre.
TEST(SensorModelGeometry, SpecularHighlightLosesDepth) {
  const std::uint32_t w = 80, h = 60;
  const double f = 60, z0 = 1000, b = 350;
  const RenderCamera cam{w, h, f, f, (w - 1) / 2.0, (h - 1) / 2.0, 100, 5000};
  SensorImages in = flat_images(w, h);
  std::vector<int> expected(w * h);  // 1 specular, 0 kept, -1 within 0.05 degrees of the cone
  for (std::uint32_t v = 0; v < h; ++v)
    for (std::uint32_t u = 0; u < w; ++u) {
      const double p[3] = {(u - cam.cx) / f * z0, (v - cam.cy) / f * z0, z0};
      const double pl = std::hypot(p[0], p[1], p[2]), tl = std::hypot(b - p[0], p[1], p[2]);
      const double hv[3] = {-p[0] / pl + (b - p[0]) / tl, -p[1] / pl - p[1] / tl, -p[2] / pl - p[2] / tl};
      const double angle = std::acos(-hv[2] / std::hypot(hv[0], hv[1], hv[2])) * 180 / M_PI;
      const std::size_t i = v * w + u;
      in.depth_mm[i] = float(z0);
      expected[i] = std::fabs(angle - 5) < 0.05 ? -1 : angle < 5 ? 1 : 0;
    }
  SensorModel m = plain_structured_light();
  m.baseline_mm = b, m.specular_cone_deg = 5;
  const SensorOutput out = sensor_model(in, sensor_params(cam, m, 0));
  std::size_t highlight = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (expected[i] < 0) continue;
    ASSERT_EQ(out.dropout[i], std::uint8_t(expected[i] ? Dropout::specular : Dropout::valid)) << i;
    highlight += expected[i];
  }
  EXPECT_GT(highlight, 20u);
  EXPECT_LT(highlight, expected.size() / 2);
  m.specular_cone_deg = 0;  // off: all kept
  EXPECT_EQ(count_dropout(sensor_model(in, sensor_params(cam, m, 0)).dropout)[Dropout::valid], expected.size());
}

// sigma(z) = a + b z^2, combined in quadrature with the added sigma: flat planes at two depths.
TEST(SensorModelGeometry, NoiseGrowsWithTheSquareOfTheDepth) {
  const std::uint32_t w = 200, h = 150;  // 30000 samples: the sample sigma is within 0.5 %
  const RenderCamera cam{w, h, 300, 300, (w - 1) / 2.0, (h - 1) / 2.0, 100, 5000};
  SensorModel m = plain_structured_light();
  m.baseline_mm = 350;
  m.noise_a_mm = 0.2, m.noise_b_per_mm = 4e-7;
  for (double added : {0.0, 1.0}) {
    m.added_sigma_mm = added;
    double sigmas[2];
    for (int k = 0; k < 2; ++k) {
      const double z = k == 0 ? 800 : 1600;
      SensorImages in = flat_images(w, h);
      std::fill(in.depth_mm.begin(), in.depth_mm.end(), float(z));
      const SensorOutput out = sensor_model(in, sensor_params(cam, m, 1000 + k));
      EXPECT_EQ(count_dropout(out.dropout)[Dropout::valid], std::size_t(w) * h);
      const auto [mean, sigma] = residual_stats(out, z);
      const double want = std::hypot(0.2 + 4e-7 * z * z, added);
      SCOPED_TRACE(testing::Message() << "z " << z << " added " << added);
      EXPECT_NEAR(mean, 0.0, 4 * want / std::sqrt(double(w) * h));
      EXPECT_NEAR(sigma / want, 1.0, 0.02);
      sigmas[k] = sigma;
    }
    if (added == 0) {
      EXPECT_NEAR(sigmas[1] / sigmas[0], (0.2 + 4e-7 * 1600 * 1600) / (0.2 + 4e-7 * 800 * 800), 0.05);
    }
  }
}

// Without noise, measured depths lie on the quantisation lattice, within half a step.
TEST(SensorModelGeometry, QuantisationSteps) {
  const std::uint32_t w = 100, h = 80;
  const RenderCamera cam{w, h, 150, 150, (w - 1) / 2.0, (h - 1) / 2.0, 100, 5000};
  SensorImages in = flat_images(w, h);
  for (std::size_t i = 0; i < in.depth_mm.size(); ++i) in.depth_mm[i] = float(500 + 0.1877 * double(i));
  SensorModel m = plain_structured_light();
  m.baseline_mm = 0;        // no shadows: the image is not a surface
  m.edge_jump_mm = 10000;   // nor has it edges
  m.quantisation_mm = 0.5, m.quantisation_ref_mm = 0;
  SensorOutput out = sensor_model(in, sensor_params(cam, m, 0));
  std::set<float> levels;
  for (std::size_t i = 0; i < in.depth_mm.size(); ++i) {
    const float z = in.depth_mm[i], q = out.depth_mm[i];
    ASSERT_LE(std::fabs(q - z), 0.25f + 1e-3f) << i;
    ASSERT_NEAR(std::fmod(double(q), 0.5), 0.0, 1e-3) << i;
    levels.insert(q);
  }
  EXPECT_GT(levels.size(), 1000u);

  // Steps growing with z^2: 0.2 mm at 1000 mm, 0.8 mm at 2000 mm; a lattice in 1 / z.
  m.quantisation_mm = 0.2, m.quantisation_ref_mm = 1000;
  out = sensor_model(in, sensor_params(cam, m, 0));
  const double c = 1000.0 * 1000.0 / 0.2;
  for (std::size_t i = 0; i < in.depth_mm.size(); ++i) {
    const double z = in.depth_mm[i], q = out.depth_mm[i], step = z * z / c;
    ASSERT_LE(std::fabs(q - z), 0.5 * step * 1.01 + 1e-3) << i;
    ASSERT_NEAR(c / q, std::round(c / q), 2e-3) << i;
  }
  const auto step_near = [&](double z) {  // the spacing of the lattice's levels around z
    const double k = std::round(c / z);
    return c / k - c / (k + 1);
  };
  EXPECT_NEAR(step_near(1000), 0.2, 1e-3);
  EXPECT_NEAR(step_near(2000) / step_near(1000), 4.0, 0.01);
}
