// A bin given as a mesh (--bin mesh:FILE; host/detect/params/bin_mesh_interior.hpp): the interior
// of synth's built-in bin and of a wire basket whose rays pass between bars, the ray-triangle
// distance on a hand-computed case, and meshes that are no bin (or not in its frame) refused.
#include <gtest/gtest.h>

#include <filesystem>

#include "host/core/error.hpp"
#include "host/detect/params/bin_mesh_interior.hpp"
#include "host/detect/params/bin_spec.hpp"
#include "host/formats/mesh/mesh_writers.hpp"
#include "synth/bin/bin_model.hpp"
#include "tests/support/cli_run.hpp"

using namespace binpick;

TEST(BinMeshInterior, RayTriangleDistanceOnAHandComputedCase) {
  const Eigen::Vector3d a(5, -1, -1), b(5, 3, -1), c(5, -1, 3);  // the plane x = 5
  EXPECT_NEAR(ray_triangle_distance({0, 0, 0}, {1, 0, 0}, a, b, c), 5.0, 1e-12);
  EXPECT_NEAR(ray_triangle_distance({0, 0, 0}, {1, 0, 0}, a, c, b), 5.0, 1e-12);  // either side
  EXPECT_LT(ray_triangle_distance({0, 0, 0}, {-1, 0, 0}, a, b, c), 0);           // behind
  EXPECT_LT(ray_triangle_distance({0, 2.5, 2.5}, {1, 0, 0}, a, b, c), 0);        // outside
  EXPECT_LT(ray_triangle_distance({0, 0, 0}, {0, 1, 0}, a, b, c), 0);            // parallel
  EXPECT_LT(ray_triangle_distance({0, 0, 0}, {1, 0, 0}, a, a, c), 0);            // degenerate
}

TEST(BinMeshInterior, TheBuiltInBinsInteriorWhateverItsWalls) {
  for (const double wall : {5.0, 10.0, 40.0}) {
    const BinModel bin = built_in_bin({600, 400, 300}, {wall, 25.0});
    const Eigen::Vector3d size = bin_interior_from_mesh(bin.mesh);
    EXPECT_NEAR(size.x(), 600, 1e-6) << wall;
    EXPECT_NEAR(size.y(), 400, 1e-6) << wall;
    EXPECT_NEAR(size.z(), 300, 1e-6) << wall;
  }
  // Deeper than wide along x: W is still the longer side.
  const Eigen::Vector3d turned = bin_interior_from_mesh(built_in_bin({300, 500, 200}, {}).mesh);
  EXPECT_NEAR(turned.x(), 500, 1e-6);
  EXPECT_NEAR(turned.y(), 300, 1e-6);
}

// A wire basket: 4 mm bars 60 mm apart standing on a plate, four horizontal wires around; most
// rays pass between the bars or wires, and those that meet one give the inner faces.
TEST(BinMeshInterior, AWireBasketsInteriorIsWhereItsBarsAre) {
  Mesh basket;
  const double hw = 250, hd = 150, h = 200, bar = 4;
  append_box(basket, {Eigen::Vector3d(-hw - bar, -hd - bar, -bar), Eigen::Vector3d(hw + bar, hd + bar, 0)});
  for (double x = -hw; x <= hw; x += 60)
    for (const double y : {-hd - bar, hd})
      append_box(basket, {Eigen::Vector3d(x, y, 0), Eigen::Vector3d(x + bar, y + bar, h)});
  for (double y = -hd; y <= hd; y += 60)
    for (const double x : {-hw - bar, hw})
      append_box(basket, {Eigen::Vector3d(x, y, 0), Eigen::Vector3d(x + bar, y + bar, h)});
  for (const double z : {50.0, 100.0, 150.0, h - bar}) {
    append_box(basket, {Eigen::Vector3d(-hw - bar, -hd - bar, z), Eigen::Vector3d(hw + bar, -hd, z + bar)});
    append_box(basket, {Eigen::Vector3d(-hw - bar, hd, z), Eigen::Vector3d(hw + bar, hd + bar, z + bar)});
    append_box(basket, {Eigen::Vector3d(-hw - bar, -hd, z), Eigen::Vector3d(-hw, hd, z + bar)});
    append_box(basket, {Eigen::Vector3d(hw, -hd, z), Eigen::Vector3d(hw + bar, hd, z + bar)});
  }
  const Eigen::Vector3d size = bin_interior_from_mesh(basket);
  EXPECT_NEAR(size.x(), 2 * hw, 1e-6);
  EXPECT_NEAR(size.y(), 2 * hd, 1e-6);
  EXPECT_NEAR(size.z(), h, 1e-6);
}

TEST(BinMeshInterior, MeshesThatAreNoBinAreRefused) {
  Mesh open;  // a floor and three walls: nothing along +x
  append_box(open, {Eigen::Vector3d(-310, -210, -10), Eigen::Vector3d(300, 210, 0)});
  append_box(open, {Eigen::Vector3d(-310, -210, 0), Eigen::Vector3d(-300, 210, 200)});
  append_box(open, {Eigen::Vector3d(-300, -210, 0), Eigen::Vector3d(300, -200, 200)});
  append_box(open, {Eigen::Vector3d(-300, 200, 0), Eigen::Vector3d(300, 210, 200)});
  try {
    bin_interior_from_mesh(open);
    ADD_FAILURE() << "accepted a bin without its +x wall";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no wall along +x"), std::string::npos) << e.what();
  }
  Mesh below;  // a bin upside down under z = 0
  append_box(below, {Eigen::Vector3d(-300, -200, -300), Eigen::Vector3d(300, 200, -10)});
  EXPECT_THROW(bin_interior_from_mesh(below), InputError);
  EXPECT_THROW(bin_interior_from_mesh(Mesh{}), InputError);
}

// --bin mesh:FILE reads the file once and gives the sized fit its interior; a missing or
// malformed file is one message naming it.
TEST(BinMeshInterior, BinMeshTextGivesTheSizedSpec) {
  const auto dir = test::fresh_temp_dir("bin_mesh_text");
  const auto ply = dir / "tote.ply";
  write_ply(ply, built_in_bin({600, 400, 300}, {}).mesh);
  const BinSpec spec = parse_bin("mesh:" + ply.string());
  EXPECT_EQ(spec.mode, BinSpec::Mode::sized);
  EXPECT_NEAR((spec.size - Eigen::Vector3d(600, 400, 300)).norm(), 0, 1e-3);
  for (const std::string bad : {"mesh:" + (dir / "none.ply").string(), std::string("mesh:")}) {
    try {
      parse_bin(bad);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
  std::filesystem::remove_all(dir);
}
