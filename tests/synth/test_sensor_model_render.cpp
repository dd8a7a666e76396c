// The structured-light sensor model on a rendered pile of built-in parts (lavapipe): device and
// reference agree, and every effect takes its share of the pixels.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include "host/runtime/vk/vk_context.hpp"
#include "synth/parts/builtin_parts.hpp"
#include "synth/render/bin_renderer.hpp"
#include "synth/sensor/sensor_apply.hpp"

using namespace binpick;

namespace {

// Parts at random orientations between 60 and 160 mm above the floor of the paper's bin (the
// camera 1000 mm above the floor): overlapping, but a pile as far as the camera can tell.
std::vector<Eigen::Isometry3d> random_pile(int parts, std::mt19937& rng) {
  std::uniform_real_distribution<double> x(-260, 260), y(-170, 170), z(840, 940), angle(-M_PI, M_PI);
  std::vector<Eigen::Isometry3d> poses;
  for (int k = 0; k < parts; ++k) {
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    const Eigen::Vector3d axis = Eigen::Vector3d(angle(rng), angle(rng), angle(rng)).normalized();
    p.linear() = Eigen::AngleAxisd(angle(rng), axis).toRotationMatrix();
    p.translation() = Eigen::Vector3d(x(rng), y(rng), z(rng));
    poses.push_back(p);
  }
  return poses;
}

}  // namespace

TEST(SensorModelRender, PileOfBrackets) {
  std::mt19937 rng(21);
  const RenderCamera camera = camera_for_bin(600, 400, 300, 1000, 640, 360);
  RenderOptions options;
  options.count_unoccluded = false;
  const RenderedBin rendered = render_bin(make_builtin_part("bracket"), random_pile(250, rng), camera, options);
  SensorModel model;
  model.kind = SensorModel::Kind::structured_light;
  RenderedBin device = rendered, reference = rendered;
  const DropoutCounts counts = apply_sensor_model(vkrt::Context::shared(), camera, model, 3, device);
  const DropoutCounts want = apply_sensor_model_reference(camera, model, 3, reference);
  std::cout << "pile of 250 brackets, " << camera.width << " x " << camera.height
            << ", default structured light: " << counts.summary() << "\n";
  EXPECT_EQ(counts.pixels, want.pixels);
  for (std::size_t i = 0; i < device.depth_mm.size(); ++i) {
    ASSERT_EQ(device.depth_mm[i] > 0, reference.depth_mm[i] > 0) << i;
    ASSERT_EQ(device.gray[i], reference.gray[i]) << i;
    // The device's log and cos may move a depth across a rounding boundary: one step at most.
    const double z = reference.depth_mm[i] / model.quantisation_ref_mm;
    ASSERT_NEAR(device.depth_mm[i], reference.depth_mm[i], 1.01 * model.quantisation_mm * z * z + 1e-3) << i;
  }
  const double surface = double(counts.surface());
  EXPECT_GT(surface, 0.2 * double(device.depth_mm.size()));
  EXPECT_GT(counts[Dropout::valid] / surface, 0.3);
  EXPECT_LT(counts[Dropout::valid] / surface, 0.95);
  for (Dropout d : {Dropout::shadow, Dropout::grazing, Dropout::edge})
    EXPECT_GT(counts[d] / surface, 0.01) << dropout_name(d);
  EXPECT_EQ(counts[Dropout::out_of_range], 0u);
  const auto valid = valid_pixels_per_part(device);
  std::size_t total = 0;
  for (std::size_t k = 0; k < valid.size(); ++k) {
    EXPECT_LE(valid[k], device.px_visible[k]);
    total += valid[k];
  }
  EXPECT_EQ(total, counts[Dropout::valid]);  // only parts are drawn
}
