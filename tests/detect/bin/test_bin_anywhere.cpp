// A bin found anywhere in view (host/detect/bin/bin_anywhere.cpp, through fit_bin with
// --bin W,D,H, --bin mesh:FILE and --bin auto): small in the image, turned, tilted, in front of clutter that stands
// higher than its rim; and no bin said where there is none.
#include <gtest/gtest.h>

#include "host/detect/bin/bin_fit.hpp"
#include "tests/detect/bin/bin_fit_check.hpp"
#include "tests/detect/bin/bin_scene.hpp"
#include "tests/support/cli_run.hpp"
#include "host/formats/mesh/mesh_writers.hpp"
#include "synth/bin/bin_model.hpp"
#include "host/detect/params/bin_spec.hpp"

#include <filesystem>

using namespace binpick;
using namespace binpick::test;

namespace {

// The bin a third of the image wide, 2 m off, in a cell: a wall behind it (a fence), a robot's
// column beside it higher than the rim, a crate on the other side.
BinSceneSpec cell_spec(double tilt, double yaw) {
  BinSceneSpec s;
  s.distance = 2000, s.tilt_deg = tilt, s.yaw_deg = yaw;
  const double hw = s.W / 2, hd = s.D / 2;
  s.boxes = {{{-1500, hd + 600, -40}, {1500, hd + 640, 1400}},      // the fence
             {{-hw - 600, -150, -40}, {-hw - 350, 150, 700}},       // the robot's column
             {{hw + 300, -200, -40}, {hw + 650, 150, 140}}};        // a crate
  return s;
}

}  // namespace

TEST(BinAnywhere, FindsASmallTurnedBinInFrontOfClutterFromItsSize) {
  for (const auto& [tilt, yaw] : {std::pair{25.0, 25.0}, {15.0, -35.0}, {0.0, 40.0}}) {
    SCOPED_TRACE(testing::Message() << "tilt " << tilt << " yaw " << yaw);
    const BinSceneSpec s = cell_spec(tilt, yaw);
    const BinScene scene = make_bin_scene(s);
    const BinFit b = fit(scene, {BinSpec::Mode::sized, {s.W, s.D, s.H}});
    expect_matches(b, scene, s, false);
  }
}

// The same from the bin's mesh (--bin mesh:FILE): synth's built-in bin of that interior, written
// as a PLY file, gives the sized fit its size.
TEST(BinAnywhere, FindsASmallTurnedBinInFrontOfClutterFromItsMesh) {
  const auto dir = fresh_temp_dir("bin_anywhere_mesh");
  const BinSceneSpec s = cell_spec(25, 25);
  const auto ply = dir / "bin.ply";
  write_ply(ply, built_in_bin({s.W, s.D, s.H}, {s.wall, 25.0}).mesh);
  const BinScene scene = make_bin_scene(s);
  const BinFit b = fit(scene, parse_bin("mesh:" + ply.string()));
  expect_matches(b, scene, s, false);
  std::filesystem::remove_all(dir);
}

TEST(BinAnywhere, FindsASmallTurnedBinInFrontOfClutterWithoutItsSize) {
  for (const auto& [tilt, yaw] : {std::pair{25.0, 25.0}, {15.0, -35.0}, {0.0, 40.0}}) {
    SCOPED_TRACE(testing::Message() << "tilt " << tilt << " yaw " << yaw);
    const BinSceneSpec s = cell_spec(tilt, yaw);
    const BinScene scene = make_bin_scene(s);
    const BinFit b = fit(scene, {BinSpec::Mode::find, {}});
    expect_matches(b, scene, s, true);
    EXPECT_TRUE(b.anywhere);
  }
}

TEST(BinAnywhere, AnEmptyFrameAlongTheBorderIsLookedPast) {
  // A bin filling the view: with parts, the border's frame stands; empty, it holds nothing, so the
  // search anywhere runs too (in a cell, an empty tray along the border is not the bin to pick
  // from) and here finds the same bin.
  BinSceneSpec s;
  s.tilt_deg = 20;
  const BinFit full = fit(make_bin_scene(s), {BinSpec::Mode::find, {}});
  ASSERT_TRUE(full.found) << full.why;
  EXPECT_FALSE(full.anywhere);
  s.spheres.clear();
  const BinScene empty_scene = make_bin_scene(s);
  const BinFit empty = fit(empty_scene, {BinSpec::Mode::find, {}});
  expect_matches(empty, empty_scene, s, true);
  EXPECT_TRUE(empty.anywhere);
}

TEST(BinAnywhere, NoBinIsSaidWhereThereIsNone) {
  // A heap on the ground, and the cell without its bin (only the walls' clutter).
  for (int k = 0; k < 2; ++k) {
    BinSceneSpec s = k == 0 ? heap_spec(3) : cell_spec(20, 10);
    if (k == 1) s.W = 0.5, s.D = 0.5, s.H = 0.5, s.wall = 0, s.spheres.clear();
    for (const BinSpec& spec : {BinSpec{BinSpec::Mode::sized, {400, 300, 180}}, BinSpec{BinSpec::Mode::find, {}}}) {
      const BinFit b = fit(make_bin_scene(s), spec);
      EXPECT_FALSE(b.found) << describe(b);
    }
  }
}
