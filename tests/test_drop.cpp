// The Bullet drop: small bins (a full 350-part bin is the benchmark's job, DESIGN.md 7).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <numbers>
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

namespace binpick {
namespace {

// An L-profile (legs 40 and 30 mm, 5 mm thick) extruded 20 mm: a bracket-like part of
// diameter about 54 mm, concave, closed, wound counter-clockwise from outside.
Mesh l_bracket() {
  const std::vector<Eigen::Vector2f> outline = {{0, 0}, {40, 0}, {40, 5}, {5, 5}, {5, 30}, {0, 30}};
  const float width = 20;
  const auto n = static_cast<std::uint32_t>(outline.size());
  Mesh m;
  for (float z : {0.0f, width})
    for (const auto& p : outline) m.positions.emplace_back(p.x(), p.y(), z);
  // Fan from the reflex corner (index 3), which sees every other corner.
  for (std::uint32_t i : {4u, 5u, 0u, 1u}) {
    const std::uint32_t j = (i + 1) % n;
    m.triangles.push_back({3, j, i});              // bottom, facing -z
    m.triangles.push_back({n + 3, n + i, n + j});  // top, facing +z
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    m.triangles.push_back({i, j, n + j});
    m.triangles.push_back({i, n + j, n + i});
  }
  return m;
}

Mesh box(const Eigen::Vector3f& size) {
  Mesh m;
  for (int i = 0; i < 8; ++i)
    m.positions.emplace_back(i & 1 ? size.x() : 0.f, i & 2 ? size.y() : 0.f,
                             i & 4 ? size.z() : 0.f);
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

// Ring radius 20 mm, tube radius 6 mm: diameter 52 mm, like the paper's part; 8 HACD hulls.
Mesh torus() {
  const int nu = 32, nv = 12;
  Mesh m;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * std::numbers::pi * i / nu, v = 2 * std::numbers::pi * j / nv;
      m.positions.emplace_back(float((20 + 6 * std::cos(v)) * std::cos(u)),
                               float((20 + 6 * std::cos(v)) * std::sin(u)), float(6 * std::sin(v)));
    }
  const auto at = [&](int i, int j) { return std::uint32_t((i % nu) * nv + j % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

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
// all-dynamic final settling nothing may go anywhere; with frozen parts to the end, a part
// may shift a little under weight it never felt (DropOptions::freeze_resting), not more.
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
    EXPECT_LT((now.translation() - before.translation()).norm(), (exact ? 0.05 : 0.15) * diameter)
        << "part " << i;
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
  rejects([](DropOptions& o) { o.bin_size_mm = {40, 40, 40}; });  // narrower than the part
  EXPECT_THROW(drop_parts(ConvexParts{}, l_bracket(), small_bin()), InputError);
  EXPECT_THROW(drop_parts(bracket_hulls(), Mesh{}, small_bin()), InputError);
}

}  // namespace
}  // namespace binpick
