// The bin in the rendered scene and several kinds of part (lavapipe, validation on): the
// built-in bin's geometry, its rim at the depth the geometry gives under straight and tilted
// cameras, its pixels a surface of no part, part counts unchanged by it, and instances of
// several meshes keeping their own ids.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <optional>

#include "host/core/error.hpp"
#include "synth/bin/bin_model.hpp"
#include "synth/camera_rig.hpp"
#include "synth/render/bin_renderer.hpp"

using namespace binpick;

namespace {
const bool validation_on = [] { return setenv("BINPICK_VK_VALIDATION", "1", 1) == 0; }();

const Eigen::Vector3d kInterior(300, 200, 150);

Mesh box_mesh(const Eigen::Vector3d& half) {
  Mesh m;
  append_box(m, Eigen::AlignedBox3d(-half, half));
  return m;
}

Eigen::Isometry3d at(const Eigen::Vector3d& t, double angle_deg = 0) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.linear() = Eigen::AngleAxisd(angle_deg * M_PI / 180, Eigen::Vector3d(1, 1, 0).normalized())
                   .toRotationMatrix();
  p.translation() = t;
  return p;
}

// A 320 x 180 camera that sees the whole bin, rim included.
CameraRig wide_rig(double tilt_deg) {
  CameraRig rig;
  rig.width = 320;
  rig.height = 180;
  rig.tilt_deg = tilt_deg;
  rig.intrinsics = std::array<double, 4>{200.0, 200.0, 159.5, 89.5};
  return rig;
}

std::size_t pixel(const RenderedBin& r, long u, long v) {
  return std::size_t(v) * r.width + std::size_t(u);
}

// Where the ray through pixel (u, v)'s centre meets the horizontal plane z_w = z: its depth.
double depth_on_plane(const SceneView& view, long u, long v, double z) {
  const Eigen::Vector3d ray((u - view.camera.cx) / view.camera.fx,
                            (v - view.camera.cy) / view.camera.fy, 1.0);
  const Eigen::Isometry3d c2w = view.world_to_camera.inverse();
  const Eigen::Vector3d origin = c2w.translation(), dir = c2w.linear() * ray;
  return (z - origin.z()) / dir.z();  // dir has z = 1 in the camera frame: t is the depth
}
}  // namespace

TEST(BuiltInBin, BoxesMakeWallsRimAndFloor) {
  const BinModel bin = built_in_bin(kInterior, {10, 25});
  // The outer footprint is the interior plus walls plus lip on every side; the top is the rim.
  EXPECT_TRUE(bin.bounds.min().isApprox(Eigen::Vector3d(-185, -135, -10)));
  EXPECT_TRUE(bin.bounds.max().isApprox(Eigen::Vector3d(185, 135, 150)));
  // The interior is empty: no box reaches into it.
  const Eigen::AlignedBox3d interior(Eigen::Vector3d(-150, -100, 0),
                                     Eigen::Vector3d(150, 100, 150));
  for (const auto& b : bin.boxes) EXPECT_LE(b.intersection(interior).volume(), 0.0);
  EXPECT_EQ(bin.mesh.triangles.size(), bin.boxes.size() * 12);
  EXPECT_FALSE(bin.double_sided);
  EXPECT_EQ(built_in_bin(kInterior, {10, 0}).boxes.size(), 5u);  // no lip
  EXPECT_THROW(built_in_bin(kInterior, {0, 25}), InputError);
  EXPECT_THROW(built_in_bin(kInterior, {10, std::nan("")}), InputError);
  EXPECT_THROW(bin_from_mesh(Mesh{}), InputError);
}

TEST(CameraRig, TiltKeepsTheFloorCentreOnTheAxisAtTheSameDistance) {
  for (const double tilt : {0.0, 20.0, -35.0}) {
    const Eigen::Isometry3d w2c = world_to_camera(1000, tilt);
    EXPECT_TRUE((w2c * Eigen::Vector3d::Zero()).isApprox(Eigen::Vector3d(0, 0, 1000), 1e-9))
        << tilt;
    const Eigen::Vector3d centre = w2c.inverse().translation();
    const double t = tilt * M_PI / 180;
    EXPECT_TRUE(centre.isApprox(Eigen::Vector3d(0, -1000 * std::sin(t), 1000 * std::cos(t)), 1e-9))
        << tilt;
    // The image's x axis stays the world's x axis.
    EXPECT_TRUE(
        (w2c.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitX(), 1e-12));
  }
  CameraRig bad;
  bad.tilt_deg = std::nan("");
  EXPECT_THROW(validate_camera_rig(bad), InputError);
  bad.tilt_deg = 85;
  EXPECT_THROW(validate_camera_rig(bad), InputError);
  bad.tilt_deg = 0;
  bad.intrinsics = std::array<double, 4>{-1, 100, 10, 10};
  EXPECT_THROW(validate_camera_rig(bad), InputError);
}

TEST(CameraRig, RollTurnsTheBinInTheImageAboutTheOpticalAxis) {
  for (const double tilt : {0.0, 25.0}) {
    const Eigen::Isometry3d plain = world_to_camera(2000, tilt);
    const Eigen::Isometry3d rolled = world_to_camera(2000, tilt, 30);
    // The floor's centre stays on the axis at the same distance; the camera stays where it was.
    EXPECT_TRUE((rolled * Eigen::Vector3d::Zero()).isApprox(Eigen::Vector3d(0, 0, 2000), 1e-9));
    EXPECT_TRUE(rolled.inverse().translation().isApprox(plain.inverse().translation(), 1e-9));
    // The bin's x axis, drawn along the image's x without a roll, now rises 30 degrees up the
    // image (image y points down): counter-clockwise as seen.
    const Eigen::Vector3d x = rolled.linear() * Eigen::Vector3d::UnitX();
    EXPECT_NEAR(std::atan2(-x.y(), x.x()) * 180 / M_PI, 30.0, 1e-9) << tilt;
    EXPECT_NEAR(x.z(), 0.0, 1e-12);
  }
  EXPECT_TRUE(world_to_camera(1000, 10, 0).isApprox(world_to_camera(1000, 10)));
  CameraRig bad;
  bad.roll_deg = 181;
  EXPECT_THROW(validate_camera_rig(bad), InputError);
  bad.roll_deg = std::nan("");
  EXPECT_THROW(validate_camera_rig(bad), InputError);
}

TEST(CameraRig, ClippingPlanesEncloseTheBinAtAnyTilt) {
  const BinModel bin = built_in_bin(kInterior, {10, 25});
  for (const double tilt : {0.0, 30.0, -60.0, 80.0}) {
    const SceneView view = scene_view(wide_rig(tilt), kInterior, bin.bounds);
    for (int c = 0; c < 8; ++c) {
      const double z =
          (view.world_to_camera * bin.bounds.corner(Eigen::AlignedBox3d::CornerType(c))).z();
      EXPECT_GT(z, view.camera.near_mm) << tilt;
      EXPECT_LT(z, view.camera.far_mm) << tilt;
    }
  }
  // Untilted, the default camera is camera_for_bin's, the near plane as before.
  CameraRig rig;
  const SceneView view = scene_view(rig, kInterior, bin.bounds);
  const RenderCamera want = camera_for_bin(300, 200, 150, 1000, 1600, 900);
  EXPECT_EQ(view.camera.fx, want.fx);
  EXPECT_EQ(view.camera.cx, want.cx);
  EXPECT_EQ(view.camera.near_mm, want.near_mm);
}

// The rim's top face at the depth where the pixel's ray meets its plane, the floor likewise;
// both are surfaces of no part (instance -1). The straight-down camera and two tilted ones.
TEST(RenderBinScene, RimAndFloorAtTheirDepthAndNoPart) {
  ASSERT_TRUE(validation_on);
  const BinModel bin = built_in_bin(kInterior, {10, 25});
  for (const double tilt : {0.0, 25.0, -40.0}) {
    SCOPED_TRACE("tilt " + std::to_string(tilt));
    const SceneView view = scene_view(wide_rig(tilt), kInterior, bin.bounds);
    BinRenderer renderer({box_mesh({10, 10, 10})}, &bin, view.camera);
    const RenderedBin r = renderer.render_scene({{}, {}, view.world_to_camera});
    // Points in the middle of the lip on the +x and -y sides, and of the floor near +x.
    for (const Eigen::Vector3d& world :
         {Eigen::Vector3d(150 + 10 + 12.5, 20, 150), Eigen::Vector3d(30, -100 - 10 - 12.5, 150),
          Eigen::Vector3d(100, 0, 0)}) {
      const Eigen::Vector2d uv = project(view.camera, view.world_to_camera * world);
      const long u = std::lround(uv.x()), v = std::lround(uv.y());
      ASSERT_TRUE(u >= 0 && v >= 0 && u < 320 && v < 180) << world.transpose();
      const std::size_t i = pixel(r, u, v);
      if (world.z() == 0 && tilt < 0) continue;  // the floor near +x may hide behind the -y wall
      EXPECT_NEAR(r.depth_mm[i], depth_on_plane(view, u, v, world.z()), 0.05) << world.transpose();
      EXPECT_EQ(r.instance[i], -1);
      EXPECT_GT(r.gray[i], 0);
    }
    // Beyond the lip: nothing.
    EXPECT_EQ(r.depth_mm[pixel(r, 0, 0)], 0.0f);
  }
}

// Parts in the bin: their pixels are counted as without the bin (the bin hides none of them,
// seen from above), the bin's pixels for none, and every counted pixel carries its part's index.
TEST(RenderBinScene, BinPixelsCountForNoPart) {
  const BinModel bin = built_in_bin(kInterior, {10, 25});
  CameraRig rig = wide_rig(0);
  rig.intrinsics = std::array<double, 4>{500.0, 500.0, 159.5, 89.5};  // the bin fills the image
  const SceneView view = scene_view(rig, kInterior, bin.bounds);
  // Clear of the floor and of each other.
  const std::vector<Eigen::Isometry3d> world{at({-60, 20, 40}, 30), at({50, -40, 40}, 70),
                                             at({60, 50, 60})};
  std::vector<Eigen::Isometry3d> parts;
  for (const auto& p : world) parts.push_back(view.world_to_camera * p);
  BinRenderer renderer({box_mesh({20, 12, 8})}, &bin, view.camera);
  const RenderedBin with = renderer.render_scene({parts, {}, view.world_to_camera});
  const RenderedBin without = renderer.render_scene({parts, {}, std::nullopt});
  EXPECT_EQ(with.px_visible, without.px_visible);
  EXPECT_EQ(with.px_all, without.px_all);
  EXPECT_EQ(with.bbox_visible, without.bbox_visible);
  std::size_t bin_pixels = 0, background = 0;
  std::vector<std::uint32_t> counted(parts.size(), 0);
  for (std::size_t i = 0; i < with.instance.size(); ++i) {
    if (with.instance[i] >= 0)
      ++counted[std::size_t(with.instance[i])];
    else if (with.depth_mm[i] > 0)
      ++bin_pixels;
    else
      ++background;
    EXPECT_EQ(with.instance[i], without.instance[i]) << i;
    if (without.depth_mm[i] > 0) {
      EXPECT_EQ(with.depth_mm[i], without.depth_mm[i]) << i;
    }
  }
  EXPECT_EQ(counted, with.px_visible);
  EXPECT_GT(bin_pixels, with.instance.size() / 2);  // the floor, walls and rim fill most of it
  EXPECT_GT(background, 0u);                        // around the bin
  for (const auto px : with.px_visible) EXPECT_GT(px, 50u);
}

// Kinds drawn as one instanced draw each keep their parts' indices: the scene of two kinds is
// pixel for pixel the union of each kind rendered alone (the parts do not overlap).
TEST(RenderBinScene, SeveralMeshesKeepTheirInstanceIds) {
  const RenderCamera camera = camera_for_bin(300, 200, 150, 1000, 320, 180);
  const Mesh small = box_mesh({8, 8, 8}), large = box_mesh({25, 15, 10});
  const std::vector<Eigen::Isometry3d> poses{at({-80, 0, 900}, 20), at({0, 0, 880}, 40),
                                             at({80, 30, 920}, 60)};
  const std::vector<int> kinds{1, 0, 1};
  BinRenderer both({small, large}, nullptr, camera);
  const RenderedBin r = both.render_scene({poses, kinds, std::nullopt});
  BinRenderer only_small(small, camera), only_large(large, camera);
  for (std::size_t k = 0; k < poses.size(); ++k) {
    BinRenderer& alone = kinds[k] == 0 ? only_small : only_large;
    const RenderedBin a = alone.render({poses[k]});
    EXPECT_EQ(r.px_visible[k], a.px_visible[0]) << k;
    EXPECT_EQ(r.px_all[k], a.px_all[0]) << k;
    EXPECT_EQ(r.bbox_visible[k], a.bbox_visible[0]) << k;
    for (std::size_t i = 0; i < a.instance.size(); ++i) {
      if (a.instance[i] != 0) continue;
      ASSERT_EQ(r.instance[i], int(k)) << "part " << k << " pixel " << i;
    }
  }
  EXPECT_GT(r.px_visible[0], 2 * r.px_visible[1]);  // the large box is larger
  EXPECT_THROW(both.render_scene({poses, {0, 2, 0}, std::nullopt}), InputError);
  EXPECT_THROW(both.render_scene({poses, {0, 1}, std::nullopt}), InputError);
}
