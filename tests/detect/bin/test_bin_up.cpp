// "Up" from the rim alone (host/detect/bin/bin_up.cpp) on analytic bins (bin_scene.hpp): the rim's
// support peaks at the true up and falls off a degree or two away; the search finds the true
// up with the floor buried under balls (no plane to take it from), straight down and tilted;
// it keeps to its cone; and says nothing without a border band.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "host/detect/bin/bin_up.hpp"
#include "host/detect/scene/scene_prepare.hpp"
#include "tests/detect/bin/bin_scene.hpp"

using namespace binpick;
using namespace binpick::test;

namespace {

double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

PlaneSamples samples_of(const BinScene& scene) {
  const PointImage pts = depth_to_points_reference(scene.depth, scene.cam);
  return sample_points(pts.xyzw, pts.width, pts.height);
}

// A bin full of balls of 25-45 mm up to under the rim: the floor hidden, no plane but the walls
// and the ground.
BinSceneSpec full_of_balls(double tilt) {
  BinSceneSpec s;
  s.tilt_deg = tilt;
  s.distance = 900;
  s.spheres.clear();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 150; ++i) {
    const double r = 25 + 20 * unit(rng);
    s.spheres.push_back({(unit(rng) - 0.5) * (s.W - 2 * r), (unit(rng) - 0.5) * (s.D - 2 * r),
                         r + unit(rng) * (s.H - 15 - 2 * r), r});
  }
  return s;
}

}  // namespace

TEST(BinUp, SupportPeaksAtTheTrueUp) {
  BinSceneSpec s;
  s.tilt_deg = 20;
  const BinScene scene = make_bin_scene(s);
  const BorderBand band = border_band(samples_of(scene), 0.25);
  const Eigen::Vector3d up = scene.bin_to_cam.col(2);
  const double tol = 3.0;
  const std::size_t at_up = rim_support(band, up, tol);
  ASSERT_GT(at_up, 200u);
  for (double off : {1.0, 3.0, 10.0})
    for (const Eigen::Vector3d& axis : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)}) {
      SCOPED_TRACE(testing::Message() << off << " degrees about " << axis.transpose());
      const Eigen::Vector3d tipped = Eigen::AngleAxisd(off * M_PI / 180, axis) * up;
      // A degree off still holds most of the rim (the 3-bin sum spans 9 mm); 3 off, not.
      EXPECT_LT(double(rim_support(band, tipped, tol)), (off < 2 ? 0.95 : 0.8) * double(at_up));
    }
  // Wider bins hold at least as many samples at the true up.
  EXPECT_GE(rim_support(band, up, 3 * tol), at_up);
}

TEST(BinUp, FindsUpWithTheFloorBuried) {
  for (double tilt : {0.0, 15.0, 30.0}) {
    SCOPED_TRACE(testing::Message() << "tilt " << tilt);
    const BinScene scene = make_bin_scene(full_of_balls(tilt));
    RimUpSearch opt;
    opt.tol = 2.5;
    const std::optional<RimUp> found = search_rim_up(samples_of(scene), opt);
    ASSERT_TRUE(found);
    EXPECT_LT(angle_deg(found->up, scene.bin_to_cam.col(2)), 0.5);
    EXPECT_GT(found->support, 100u);
    // The same samples, the same answer.
    EXPECT_EQ(search_rim_up(samples_of(scene), opt)->up, found->up);
  }
}

TEST(BinUp, KeepsToItsCone) {
  const BinScene scene = make_bin_scene(full_of_balls(30.0));
  RimUpSearch opt;
  opt.tol = 2.5;
  opt.max_tilt_deg = 20;
  const std::optional<RimUp> found = search_rim_up(samples_of(scene), opt);
  // The true up is 30 degrees off the optical axis, beyond the cone, and no other direction
  // within it puts a structure at one height along three sides of the border.
  EXPECT_FALSE(found) << found->up.transpose();
  opt.max_tilt_deg = 40;
  ASSERT_TRUE(search_rim_up(samples_of(scene), opt));
}

TEST(BinUp, NothingWithoutABorderBand) {
  EXPECT_FALSE(search_rim_up(PlaneSamples{}, RimUpSearch{}));
  EXPECT_EQ(rim_support(BorderBand{}, Eigen::Vector3d(0, 0, -1), 3.0), 0u);
  // Samples only in the image's middle: none in the band.
  PlaneSamples s;
  s.width = 100, s.height = 100;
  for (std::uint32_t v = 40; v < 60; ++v)
    for (std::uint32_t u = 40; u < 60; ++u) {
      s.points.emplace_back(float(u), float(v), 1000.0f);
      s.u.push_back(u), s.v.push_back(v);
    }
  EXPECT_TRUE(border_band(s, 0.25).points.empty());
  EXPECT_FALSE(search_rim_up(s, RimUpSearch{}));
}
