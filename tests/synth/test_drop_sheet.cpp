// A pile of thin sheet-metal parts (builtin:plate, 1.5 mm thick, 120 mm across) comes to rest
// within its limits. Plates stacked flat used to keep every wave running into its limit: their
// velocities never settled though their poses did (rest_tracker.hpp), and a landing wave woke
// the whole shallow pile (pile_freezer.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "synth/decompose/decompose.hpp"
#include "synth/parts/builtin_parts.hpp"
#include "synth/physics/drop.hpp"
#include "synth/physics/penetration.hpp"

namespace binpick {
namespace {

TEST(DropSheet, PlatePileComesToRestWithinItsLimits) {
  const Mesh plate = make_builtin_part("plate");
  DecomposeOptions d;
  d.use_cache = false;  // tests must not depend on $HOME
  const ConvexParts hulls = decompose_convex(plate, d);

  // Ten waves of four into a floor that holds about ten plates a layer: four layers and more,
  // where a thin part lies on thin parts.
  DropOptions o;
  o.bin_size_mm = {300, 200, 150};
  o.grid_x = 2;
  o.grid_y = 2;
  o.objects = 40;
  o.drop_height_mm = 200;
  o.max_wave_seconds = 20;  // a wave takes 1 to 3 simulated seconds; one took over 30
  const DropResult result = drop_parts(hulls, plate, o);
  EXPECT_TRUE(result.stats.settled) << result.stats.message;
  EXPECT_TRUE(result.stats.sheet_pile);  // the plate's hulls are 1.5 mm thick: not released
  EXPECT_EQ(result.stats.parts_left_bin, 0) << result.stats.message;
  ASSERT_EQ(result.poses.size(), 40u);
  EXPECT_LT(result.stats.simulated_seconds, 40.0);  // 16 (84 before, one wave cut at 30)
  // Plates passing through each other would show in the depth images. Released all at once
  // after the last wave, as thicker parts are, two of these plates overlapped by 1.8 mm, more
  // than the sheet is thick; now the deepest overlap is 0.7 mm (drop.hpp, sheet_hull_mm).
  EXPECT_LT(deepest_penetration_mm(hulls, result.poses), 1.0);
  for (const auto& pose : result.poses) {
    EXPECT_NEAR(pose.linear().determinant(), 1.0, 1e-9);
    EXPECT_LE(std::abs(pose.translation().x()), 0.5 * o.bin_size_mm.x());
    EXPECT_LE(std::abs(pose.translation().y()), 0.5 * o.bin_size_mm.y());
    EXPECT_GT(pose.translation().z(), -1.0);  // lies on the floor, at most sunk into it a little
  }
}

}  // namespace
}  // namespace binpick
