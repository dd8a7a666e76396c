// bop_toolkit_sampling: with it, pixel (i, j) samples the point (i + 0.5, j + 0.5) of the
// image's intrinsics, as the BOP toolkit's renderers do; without it, (i, j). A flat face whose
// projected edges lie at known fractional coordinates tells the two apart, on lavapipe and on
// the plain C++ rasteriser alike.
#include <gtest/gtest.h>

#include <algorithm>

#include "host/core/mesh_normals.hpp"
#include "synth/render/bin_renderer.hpp"
#include "synth/render/part_silhouette.hpp"
#include "tests/support/test_meshes.hpp"

namespace binpick {
namespace {

// Columns and rows a silhouette covers: min u, max u, min v, max v.
std::array<std::uint32_t, 4> extent(const PartSilhouette& s, std::uint32_t width) {
  std::array<std::uint32_t, 4> e{~0u, 0, ~0u, 0};
  for (std::uint32_t p : s.pixels) {
    e[0] = std::min(e[0], p % width);
    e[1] = std::max(e[1], p % width);
    e[2] = std::min(e[2], p / width);
    e[3] = std::max(e[3], p / width);
  }
  return e;
}

struct FacingBox {
  // 64 x 48 image, f = 100 px, principal point at the centre; a 100 x 100 x 10 mm box whose
  // near face, at 500 mm, projects to u in [20.2, 40.2] and v in [10.2, 30.2] (u = x / 5 +
  // 31.5); its sides project inside that square.
  RenderCamera camera{64, 48, 100, 100, 31.5, 23.5, 100, 2000};
  Mesh mesh = test::box({100, 100, 10});
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  FacingBox() {
    compute_crease_normals(mesh);
    pose.translation() = Eigen::Vector3d(-56.5, -66.5, 500);
  }
};

}  // namespace

TEST(BopToolkitSampling, MovesThePrincipalPointByMinusHalfAPixel) {
  const RenderCamera c{64, 48, 100, 120, 31.5, 23.5, 100, 2000};
  const RenderCamera s = bop_toolkit_sampling(c);
  EXPECT_EQ(s.cx, 31.0);
  EXPECT_EQ(s.cy, 23.0);
  EXPECT_EQ(s.fx, c.fx);
  EXPECT_EQ(s.fy, c.fy);
  EXPECT_EQ(s.width, c.width);
  EXPECT_EQ(s.near_mm, c.near_mm);
}

TEST(BopToolkitSampling, PixelsSampleHalfAPixelFurtherOnBothDevices) {
  const FacingBox box;
  using Extent = std::array<std::uint32_t, 4>;
  // Centres at integers: columns 21..40 lie within [20.2, 40.2]; at i + 0.5: columns 20..39.
  const Extent opencv{21, 40, 11, 30}, toolkit{20, 39, 10, 29};
  for (bool shifted : {false, true}) {
    const RenderCamera cam = shifted ? bop_toolkit_sampling(box.camera) : box.camera;
    const Extent want = shifted ? toolkit : opencv;
    const PartSilhouette cpu = part_silhouette_reference(box.mesh, box.pose, cam, false);
    EXPECT_EQ(extent(cpu, cam.width), want) << "reference, shifted " << shifted;
    EXPECT_EQ(cpu.pixels.size(), 20u * 20u);
    BinRenderer renderer(std::vector<Mesh>{box.mesh}, nullptr, cam, false);
    const std::vector<PartSilhouette> gpu = renderer.silhouettes({{box.pose}, {0}, std::nullopt});
    ASSERT_EQ(gpu.size(), 1u);
    EXPECT_EQ(extent(gpu[0], cam.width), want) << "lavapipe, shifted " << shifted;
    EXPECT_EQ(gpu[0].pixels, cpu.pixels);
  }
}

}  // namespace binpick
