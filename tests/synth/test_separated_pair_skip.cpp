// Skipping the contact tests of hulls that are clearly apart (separated_pair_skip.hpp) must not
// change a bin: the same poses, bit for bit, with and without it, for parts of several hulls
// (the torus: compound against compound), one hull (a box) and against the bin's walls.
#include <gtest/gtest.h>

#include "synth/decompose/decompose.hpp"
#include "synth/physics/bin_world.hpp"
#include "synth/physics/bullet_units.hpp"
#include "synth/physics/drop.hpp"
#include "synth/physics/mass_properties.hpp"
#include "synth/physics/part_shape.hpp"
#include "tests/support/test_meshes.hpp"

namespace binpick {
namespace {

DropOptions small_bin() {
  DropOptions o;
  o.bin_size_mm = {300, 240, 150};
  o.grid_x = 4;
  o.grid_y = 3;
  o.objects = 24;
  o.drop_height_mm = 200;
  return o;
}

ConvexParts hulls_of(const Mesh& part) {
  DecomposeOptions d;
  d.use_cache = false;  // tests must not depend on $HOME
  return decompose_convex(part, d);
}

void expect_same_bin_with_and_without_skip(const Mesh& part) {
  const ConvexParts hulls = hulls_of(part);
  DropOptions with = small_bin();
  DropOptions without = with;
  without.skip_apart_hulls = false;
  const DropResult a = drop_parts(hulls, part, with);
  const DropResult b = drop_parts(hulls, part, without);
  EXPECT_TRUE(a.stats.settled) << a.stats.message;
  ASSERT_EQ(a.poses.size(), b.poses.size());
  EXPECT_EQ(a.stats.simulated_seconds, b.stats.simulated_seconds);
  EXPECT_EQ(a.stats.parts_thawed, b.stats.parts_thawed);
  for (std::size_t i = 0; i < a.poses.size(); ++i)
    EXPECT_EQ(a.poses[i].matrix(), b.poses[i].matrix()) << "part " << i;
}

TEST(SeparatedPairSkip, SameBinBitForBitWithSeveralHulls) {
  expect_same_bin_with_and_without_skip(test::torus());
}

TEST(SeparatedPairSkip, SameBinBitForBitWithOneHull) {
  expect_same_bin_with_and_without_skip(test::box(Eigen::Vector3f(40, 25, 8)));
}

// In a landing wave most pairs of hulls whose boxes overlap are apart, and are skipped; the
// option turns it off.
TEST(SeparatedPairSkip, SkipsMostTestsOfAWaveAndIsOffWhenAsked) {
  const Mesh part = test::torus();
  const ConvexParts hulls = hulls_of(part);
  const PartShape shape(hulls, mass_properties(part));
  DropOptions o = small_bin();
  BinWorld world(o, shape);
  ASSERT_NE(world.apart_pair_skip(), nullptr);
  // A column of parts a little more than a part apart, falling onto the floor and each other.
  for (int k = 0; k < 6; ++k) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(0.4 * k, Eigen::Vector3d(1, 1, 0).normalized()).matrix();
    pose.translation() = Eigen::Vector3d(3.0 * k, 0, 20 + 1.2 * shape.bounding_radius_mm() * 2 * k);
    world.add_part(to_units(pose));
  }
  for (int s = 0; s < 600; ++s) world.step();
  const auto& counts = world.apart_pair_skip()->counts();
  EXPECT_GT(counts.tests, 1000);
  EXPECT_GT(counts.skipped, counts.tests / 4) << counts.skipped << " of " << counts.tests;

  o.skip_apart_hulls = false;
  const BinWorld plain(o, shape);
  EXPECT_EQ(plain.apart_pair_skip(), nullptr);
}

}  // namespace
}  // namespace binpick
