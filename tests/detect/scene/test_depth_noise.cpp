// The depth noise estimate and the scene voxel it gives (host/detect/scene/depth_noise.hpp): a tilted
// plane with known Gaussian noise, steps and holes, an image without depth, and the voxel ramp.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "host/core/error.hpp"
#include "host/detect/scene/depth_noise.hpp"

using namespace binpick;

namespace {

bp_camera camera(std::uint32_t w, std::uint32_t h) {
  bp_camera c{};
  c.width = w, c.height = h;
  c.fx = c.fy = 1000.0f, c.cx = 0.5f * float(w), c.cy = 0.5f * float(h);
  c.depth_scale = 0.1f;  // raw units of 0.1 mm
  return c;
}

// A plane tilted along both axes at about 1 m, noise sigma_mm along z, raw 0.1 mm. Every 50th
// column a 20 mm step (a part's edge, as often as in a pile of parts 100 pixels across), and
// holes (no depth) in a checker of 40 x 30 pixel blocks.
DepthImage noisy_plane(std::uint32_t w, std::uint32_t h, double sigma_mm, unsigned seed,
                       bool steps_and_holes) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma_mm);
  DepthImage d;
  d.width = w, d.height = h;
  d.raw.resize(std::size_t(w) * h);
  for (std::uint32_t v = 0; v < h; ++v)
    for (std::uint32_t u = 0; u < w; ++u) {
      double z = 1000.0 + 0.3 * u + 0.2 * v + noise(rng);
      if (steps_and_holes && (u / 50) % 2 == 1) z -= 20.0;
      const bool hole = steps_and_holes && ((u / 40 + v / 30) % 5 == 0);
      d.raw[std::size_t(v) * w + u] = hole ? 0 : std::uint16_t(std::lround(z / 0.1));
    }
  return d;
}

}  // namespace

TEST(DepthNoise, RecoversTheSigmaOfATiltedPlane) {
  const bp_camera cam = camera(400, 300);
  for (double sigma : {0.5, 2.0, 6.0}) {
    const double got = depth_noise_mm(noisy_plane(400, 300, sigma, 7, false), cam);
    // 15 000 samples: the median's standard error is about 1 %; 5 % allows for the rounding to
    // 0.1 mm and the tilt (exactly linear in z, so none).
    EXPECT_NEAR(got, sigma, 0.05 * sigma) << sigma;
  }
}

TEST(DepthNoise, StepsAndHolesDoNotInflateIt) {
  const bp_camera cam = camera(400, 300);
  // A step every 50 pixels: 2 of every 50 samples straddle one (4 %), which moves the median
  // by about 5 % (the 52nd percentile instead of the 50th), not by the 20 mm steps.
  const double got = depth_noise_mm(noisy_plane(400, 300, 2.0, 8, true), cam);
  EXPECT_NEAR(got, 2.0, 0.2);
  EXPECT_GT(got, 1.9);
}

TEST(DepthNoise, CleanImageAndTooFewSamples) {
  const bp_camera cam = camera(400, 300);
  // Quantisation alone (0.1 mm): well under any voxel.
  EXPECT_LT(depth_noise_mm(noisy_plane(400, 300, 0.0, 1, false), cam), 0.05);
  DepthImage empty;
  empty.width = 400, empty.height = 300;
  empty.raw.assign(400 * 300, 0);
  EXPECT_EQ(depth_noise_mm(empty, cam), 0.0);
  DepthImage wrong = empty;
  wrong.raw.resize(10);
  EXPECT_THROW(depth_noise_mm(wrong, cam), InputError);
}

TEST(DepthNoise, SceneVoxelFactorRamps) {
  const double voxel = 6.0;
  EXPECT_EQ(scene_voxel_factor(0.0, voxel, 1.4), 1.0);
  EXPECT_EQ(scene_voxel_factor(kNoiseVoxelStart * voxel, voxel, 1.4), 1.0);
  EXPECT_NEAR(scene_voxel_factor(0.5 * (kNoiseVoxelStart + kNoiseVoxelFull) * voxel, voxel, 1.4),
              1.2, 1e-12);
  EXPECT_EQ(scene_voxel_factor(kNoiseVoxelFull * voxel, voxel, 1.4), 1.4);
  EXPECT_EQ(scene_voxel_factor(10 * voxel, voxel, 1.4), 1.4);
  EXPECT_EQ(scene_voxel_factor(10 * voxel, voxel, 1.0), 1.0);  // off
  EXPECT_EQ(scene_voxel_factor(NAN, voxel, 1.4), 1.0);
  EXPECT_EQ(scene_voxel_factor(3.0, 0.0, 1.4), 1.0);
}
