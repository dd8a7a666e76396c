// The Bullet drop: small bins (a full 350-part bin is the benchmark's job, docs/synthesis.md).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "host/core/error.hpp"
#include "synth/decompose/decompose.hpp"
#include "synth/physics/bin_world.hpp"
#include "synth/physics/bullet_units.hpp"
#include "synth/physics/drop.hpp"
#include "synth/physics/drop_layout.hpp"
#include "synth/physics/mass_properties.hpp"
#include "synth/physics/part_shape.hpp"
#include "synth/physics/penetration.hpp"
#include "synth/physics/rest_tracker.hpp"
#include "tests/support/test_meshes.hpp"

namespace binpick {
namespace {

using test::box;
using test::l_bracket;
using test::torus;

// A small bin the tests can afford: 3 waves of a 3 x 4 grid.
DropOptions small_bin(int objects = 30) {
  DropOptions o;
  o.bin_size_mm = {300, 240, 150};
  o.grid_x = 4;
  o.grid_y = 3;
  o.objects = objects;
  o.drop_height_mm = 200;
  return o;
}

const ConvexParts& bracket_hulls() {
  static const ConvexParts hulls = [] {
    DecomposeOptions d;
    d.use_cache = false;
    return decompose_convex(l_bracket(), d);
  }();
  return hulls;
}

struct DroppedBin {
  Mesh part;
  ConvexParts hulls;
  DropOptions options;
  DropResult result;
};

// Which part, and whether the whole pile settles once more with nothing frozen at the end.
struct BinKind {
  bool bracket;  // else the torus
  bool all_dynamic_final_settle;
};

// Dropped once per test binary and kind: 5 waves, a pile more than one part deep in places.
const DroppedBin& dropped_bin(BinKind kind) {
  static std::map<std::pair<bool, bool>, DroppedBin> bins;
  auto [it, first] = bins.try_emplace({kind.bracket, kind.all_dynamic_final_settle});
  if (first) {
    DroppedBin& b = it->second;
    b.part = kind.bracket ? l_bracket() : torus();
    DecomposeOptions d;
    d.use_cache = false;  // tests must not depend on $HOME
    b.hulls = decompose_convex(b.part, d);
    b.options = small_bin(60);
    b.options.final_settle_all_dynamic = kind.all_dynamic_final_settle;
    b.result = drop_parts(b.hulls, b.part, b.options);
  }
  return it->second;
}

class DropBin : public ::testing::TestWithParam<BinKind> {
 protected:
  const DroppedBin& bin() const { return dropped_bin(GetParam()); }
};

// The rest test measures how far each part went over a sliding quarter second
// (rest_tracker.hpp).
TEST(RestTracker, JitterCancelsDriftCountsAndAStopShowsOneWindowLater) {
  const double dt = 1.0 / 120;
  RestTracker rest(0.5, 0.05, 0.25);  // units/s, rad/s, s
  const auto at = [](double x, double z, double turn) {
    return btTransform(btQuaternion(btVector3(0, 0, 1), btScalar(turn)),
                       btVector3(btScalar(x), 0, btScalar(z)));
  };
  rest.add(at(0, 0, 0));   // 0: kicked back and forth at 6 times the rest speed, going nowhere
  rest.add(at(0, 50, 0));  // 1: falls at 300 units/s, then lies still
  rest.add(at(0, 0, 0));   // 2: creeps steadily at twice the rest speed
  rest.add(at(0, 0, 0));   // 3: turns in place at twice the rest speed
  double at_rest_since = -1;  // part 1, after it stops at t = 0.5 s
  for (int step = 1; step <= 240; ++step) {
    const double t = step * dt;
    const double kick = step % 2 ? 3 * dt : 0;  // there and back in alternate steps
    rest.update(0, at(kick, 0, kick / 10), dt);
    rest.update(1, at(0, 50 - 300 * std::min(t, 0.5), 0), dt);
    rest.update(2, at(t, 0, 0), dt);
    rest.update(3, at(0, 0, 0.1 * t), dt);
    if (at_rest_since < 0 && rest.at_rest(1)) at_rest_since = t;
  }
  EXPECT_TRUE(rest.at_rest(0));
  EXPECT_FALSE(rest.at_rest(2));
  EXPECT_NEAR(rest.speed_ratio(2), 2.0, 1e-3);
  EXPECT_FALSE(rest.at_rest(3));
  EXPECT_NEAR(rest.speed_ratio(3), 2.0, 1e-3);
  // A window to forget the fall, then rest_seconds of calm: an exponential average of the
  // fall would still read over the rest speed a second later.
  EXPECT_GT(at_rest_since, 0.5 + 0.25 + 0.25 - 2 * dt);
  EXPECT_LT(at_rest_since, 0.5 + 0.25 + 0.25 + 2 * dt);
  rest.restart(0, at(0, 0, 0));
  EXPECT_FALSE(rest.at_rest(0));
}

// A thawed part was still while frozen: a jiggle of a hundredth of a millimetre in its first
// small step is not a part moving fast (it would push its frozen neighbours awake,
// pile_freezer.hpp), a real shove still is.
TEST(RestTracker, ThawedPartStartsFromAStillWindow) {
  const double dt = 1.0 / 2400;  // the adaptive step at its shortest
  RestTracker rest(0.5, 0.05, 0.25);
  const btTransform still(btQuaternion::getIdentity(), btVector3(0, 0, 0));
  const auto moved = [](double x) {
    return btTransform(btQuaternion::getIdentity(), btVector3(btScalar(x), 0, 0));
  };
  rest.add(still);
  rest.add(still);
  rest.update(0, moved(0.001), dt);  // released: judged on the step alone
  EXPECT_GT(rest.speed_ratio(0), 3.0);
  rest.restart(1, still);
  rest.update(1, moved(0.001), dt);
  EXPECT_LT(rest.speed_ratio(1), 0.1);
  EXPECT_FALSE(rest.at_rest(1));  // calm, but not yet for rest_seconds
  for (int step = 2; step <= 60; ++step) rest.update(1, moved(0.001 + 0.01 * step), dt);
  EXPECT_GT(rest.speed_ratio(1), 3.0);  // 0.6 units in 25 ms
}

TEST(MassProperties, BoxCentreAndInertia) {
  const auto props = mass_properties(box({10, 20, 40}));
  EXPECT_NEAR(props.volume, 8000.0, 1e-6);
  EXPECT_TRUE(props.principal_frame.translation().isApprox(Eigen::Vector3d(5, 10, 20), 1e-9));
  // Solid box: I/m = (b^2 + c^2)/12 about each axis, sorted ascending by the solver.
  EXPECT_NEAR(props.inertia_per_mass[0], (100.0 + 400.0) / 12, 1e-6);
  EXPECT_NEAR(props.inertia_per_mass[2], (400.0 + 1600.0) / 12, 1e-6);
  EXPECT_NEAR(props.principal_frame.linear().determinant(), 1.0, 1e-12);
}

TEST(MassProperties, InsideOutMeshGivesSameCentre) {
  Mesh flipped = l_bracket();
  for (auto& t : flipped.triangles) std::swap(t[1], t[2]);
  const auto a = mass_properties(l_bracket()), b = mass_properties(flipped);
  EXPECT_NEAR(a.volume, b.volume, 1e-6);
  EXPECT_TRUE(a.principal_frame.translation().isApprox(b.principal_frame.translation(), 1e-9));
  // L area 40*5 + 5*25 = 325 mm^2, times 20 mm.
  EXPECT_NEAR(a.volume, 6500.0, 1e-6);
}

TEST(DropLayout, InsideBinAndNotOverlapping) {
  DropOptions o = small_bin();
  o.grid_x = 12;  // denser than the part: slots must be lifted
  const double radius = 30;
  const auto at = wave_drop_positions(o, o.grid_x * o.grid_y, radius, 0.0);
  ASSERT_EQ(at.size(), 36u);
  for (std::size_t i = 0; i < at.size(); ++i) {
    EXPECT_LE(std::abs(at[i].x()) + radius, 0.5 * o.bin_size_mm.x());
    EXPECT_LE(std::abs(at[i].y()) + radius, 0.5 * o.bin_size_mm.y());
    EXPECT_GE(at[i].z(), o.drop_height_mm);
    for (std::size_t j = 0; j < i; ++j) EXPECT_GE((at[i] - at[j]).norm(), 2 * radius);
  }
}

TEST(DropLayout, PartWiderThanBinIsInputError) {
  EXPECT_THROW(wave_drop_positions(small_bin(), 12, 200, 0.0), InputError);
}

TEST_P(DropBin, AllPartsSettleInsideTheBin) {
  const auto& b = bin();
  EXPECT_TRUE(b.result.stats.settled) << b.result.stats.message;
  EXPECT_FALSE(b.result.stats.sheet_pile);  // bracket and torus: released at the end
  EXPECT_EQ(b.result.stats.parts_left_bin, 0);
  ASSERT_EQ(b.result.poses.size(), 60u);
  EXPECT_EQ(b.result.stats.waves, 5);
  const Eigen::Vector3d half = 0.5 * b.options.bin_size_mm;
  const double tolerance = 0.5;  // mm
  for (const auto& pose : b.result.poses) {
    EXPECT_NEAR(pose.linear().determinant(), 1.0, 1e-9);
    for (const auto& hull : b.hulls.hulls)
      for (const auto& v : hull.vertices) {
        const Eigen::Vector3d w = pose * v.cast<double>();
        EXPECT_LE(std::abs(w.x()), half.x() + tolerance);
        EXPECT_LE(std::abs(w.y()), half.y() + tolerance);
        EXPECT_GE(w.z(), -tolerance);
        EXPECT_LE(w.z(), b.options.bin_size_mm.z());
      }
  }
}

TEST_P(DropBin, NoDeepInterpenetration) {
  const auto& b = bin();
  EXPECT_LT(deepest_penetration_mm(b.hulls, b.result.poses), 2.0);
}

// At rest means at rest for Bullet too: put every part back as a dynamic body where it ended
// (nothing frozen, no sleeping history) and let the world run on for half a second. After an
// all-dynamic final settling nothing may go anywhere; with parts frozen again after the
// default second of it, a part may shift a little under weight it never felt
// (DropOptions::freeze_resting), not more.
TEST_P(DropBin, PartsStayPutWhenSimulatedOn) {
  const auto& b = bin();
  const PartShape shape(b.hulls, mass_properties(b.part));
  BinWorld world(b.options, shape);
  for (const auto& pose : b.result.poses) world.add_part(to_units(pose * shape.body_in_part()));
  for (double t = 0; t < 0.5;) t += world.step();
  const double diameter = 2 * shape.bounding_radius_mm();
  const bool exact = GetParam().all_dynamic_final_settle;
  for (std::size_t i = 0; i < b.result.poses.size(); ++i) {
    const Eigen::Isometry3d now =
        to_mm(world.parts()[i]->getWorldTransform()) * shape.body_in_part().inverse();
    const Eigen::Isometry3d& before = b.result.poses[i];
    // 0.1 d: in the bin with walls and a rim of boxes, one bracket resting against a wall near
    // the floor shifted 0.08 d (4.9 mm) when simulated on; 0.15 d once frozen parts wake.
    EXPECT_LT((now.translation() - before.translation()).norm(), (exact ? 0.1 : 0.15) * diameter)
        << "part " << i << " at " << before.translation().transpose();
    if (exact) {
      EXPECT_LT(Eigen::AngleAxisd(now.linear().transpose() * before.linear()).angle(), 0.25)
          << "part " << i;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Parts, DropBin,
                         ::testing::Values(BinKind{true, false}, BinKind{false, false},
                                           BinKind{true, true}, BinKind{false, true}),
                         [](const auto& info) {
                           return std::string(info.param.bracket ? "bracket" : "torus") +
                                  (info.param.all_dynamic_final_settle ? "_all_dynamic_final_settle"
                                                                       : "");
                         });

TEST(Drop, PenetrationCheckSeesOverlap) {
  std::vector<Eigen::Isometry3d> overlapping(2, Eigen::Isometry3d::Identity());
  overlapping[1].translation() = Eigen::Vector3d(0, 0, 17);  // 20 mm wide: 3 mm overlap
  EXPECT_NEAR(deepest_penetration_mm(bracket_hulls(), overlapping), 3.0, 0.5);
}

TEST(Drop, SameSeedSamePosesOtherSeedOtherPoses) {
  const auto& bin = dropped_bin({true, false});
  const auto again = drop_parts(bin.hulls, bin.part, bin.options);
  ASSERT_EQ(again.poses.size(), bin.result.poses.size());
  for (std::size_t i = 0; i < again.poses.size(); ++i)
    EXPECT_EQ(again.poses[i].matrix(), bin.result.poses[i].matrix()) << "part " << i;

  DropOptions other = bin.options;
  other.seed = bin.options.seed + 1;
  other.objects = 12;  // one wave is enough to differ
  const auto different = drop_parts(bin.hulls, bin.part, other);
  ASSERT_FALSE(different.poses.empty());
  EXPECT_FALSE(different.poses[0].isApprox(bin.result.poses[0], 1e-6));
}

// The mixed drop with one kind is the plain drop, bit for bit; with two kinds each part keeps
// its kind.
TEST(Drop, MixedDropOfOneKindIsThePlainDrop) {
  DropOptions o = small_bin(12);
  const Mesh bracket = l_bracket();
  const DropKind bracket_kind{&bracket_hulls(), &bracket};
  const auto plain = drop_parts(bracket_hulls(), bracket, o);
  const auto mixed = drop_parts({bracket_kind}, std::vector<int>(12, 0), o);
  ASSERT_EQ(mixed.poses.size(), plain.poses.size());
  for (std::size_t i = 0; i < plain.poses.size(); ++i)
    EXPECT_EQ(mixed.poses[i].matrix(), plain.poses[i].matrix()) << "part " << i;
  EXPECT_EQ(mixed.kinds, std::vector<int>(plain.poses.size(), 0));

  const Mesh ring = torus();
  DecomposeOptions d;
  d.use_cache = false;
  const ConvexParts ring_hulls = decompose_convex(ring, d);
  const std::vector<int> sequence{0, 1, 0, 1, 1, 0, 0, 0, 1, 0, 0, 0};
  const auto two = drop_parts({bracket_kind, DropKind{&ring_hulls, &ring}}, sequence, o);
  EXPECT_EQ(two.stats.parts_left_bin, 0);
  EXPECT_EQ(two.kinds, sequence);
  EXPECT_THROW(drop_parts({bracket_kind}, std::vector<int>(11, 0), o), InputError);
  EXPECT_THROW(drop_parts({bracket_kind}, std::vector<int>(12, 1), o), InputError);
}

TEST(Drop, ProgressReportsEveryWaveUntilAtRest) {
  DropOptions o = small_bin();
  o.objects = 14;  // a full wave and a partial one
  std::vector<DropProgress> seen;
  const auto result = drop_parts(bracket_hulls(), l_bracket(), o,
                                 [&](const DropProgress& p) { seen.push_back(p); });
  ASSERT_FALSE(seen.empty());
  EXPECT_EQ(seen.back().wave, 1);
  EXPECT_EQ(seen.back().waves, 2);
  EXPECT_EQ(seen.back().parts_dropped, 14);
  EXPECT_EQ(seen.back().parts_moving, 0);
  for (std::size_t i = 1; i < seen.size(); ++i)
    EXPECT_GE(seen[i].simulated_seconds, seen[i - 1].simulated_seconds);
  EXPECT_NEAR(seen.back().simulated_seconds, result.stats.simulated_seconds, 1e-9);
}

TEST(Drop, WaveTimeLimitIsReportedNotHung) {
  DropOptions o = small_bin();
  o.objects = 12;
  o.max_wave_seconds = 0.1;  // still falling then
  const auto result = drop_parts(bracket_hulls(), l_bracket(), o);
  EXPECT_FALSE(result.stats.settled);
  EXPECT_NE(result.stats.message.find("moving"), std::string::npos) << result.stats.message;
}

TEST(Drop, BadOptionsAreInputErrors) {
  const auto rejects = [&](auto change) {
    DropOptions o = small_bin();
    change(o);
    EXPECT_THROW(drop_parts(bracket_hulls(), l_bracket(), o), InputError);
  };
  rejects([](DropOptions& o) { o.bin_size_mm.x() = 0; });
  rejects([](DropOptions& o) { o.bin_size_mm.y() = -400; });
  rejects([](DropOptions& o) { o.bin_size_mm.z() = std::numeric_limits<double>::quiet_NaN(); });
  rejects([](DropOptions& o) { o.objects = 0; });
  rejects([](DropOptions& o) { o.objects = -5; });
  rejects([](DropOptions& o) { o.grid_x = 0; });
  rejects([](DropOptions& o) { o.drop_height_mm = std::numeric_limits<double>::infinity(); });
  rejects([](DropOptions& o) { o.time_step_s = std::numeric_limits<double>::quiet_NaN(); });
  rejects([](DropOptions& o) { o.rest_linear_speed_mm_s = 0; });
  rejects([](DropOptions& o) { o.final_all_dynamic_seconds = -1; });
  rejects([](DropOptions& o) { o.bin_size_mm = {40, 40, 40}; });  // narrower than the part
  EXPECT_THROW(drop_parts(ConvexParts{}, l_bracket(), small_bin()), InputError);
  EXPECT_THROW(drop_parts(bracket_hulls(), Mesh{}, small_bin()), InputError);
}

}  // namespace
}  // namespace binpick
