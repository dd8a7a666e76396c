// The sides beyond a known edge (host/detect/bin/bin_side.hpp) on hand-made samples. The rim's strip:
// the inner edge of a strip at the rim's height that runs across the frame, the nearer of two,
// and nothing where the samples at that height are a level sheet (a bin filled to the brim), a
// side of the rim running along the axis, a short piece, or too few. The wall: the inner face of
// a mesh wall's bars standing from the floor up, before the ground seen through it, and nothing
// for the ground alone or a low kerb.
#include <gtest/gtest.h>

#include <random>

#include "host/detect/bin/bin_side.hpp"

using namespace binpick;

namespace {

// Camera-like frame: up = -z, the axis = +x, across = +y; heights are -z.
constexpr double kRimZ = 1000;  // the rim's top at z = 1000 (height -1000)

struct Samples {
  PlaneSamples s;
  std::mt19937 rng{4};
  void add(double x, double y, double z) { s.points.emplace_back(float(x), float(y), float(z)); }
  // A strip of the rim's top, its inner edge at x = inner, `wide` mm wide, over y in [y0, y1].
  void strip(double inner, double wide, double y0, double y1) {
    std::uniform_real_distribution<double> u(0, 1);
    for (double y = y0; y <= y1; y += 5)
      for (double x = inner; x <= inner + wide; x += 4) add(x, y, kRimZ + 2 * (u(rng) - 0.5));
  }
  // Parts and the floor below the rim, everywhere in x in [x0, x1].
  void below(double x0, double x1) {
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 3000; ++i)
      add(x0 + (x1 - x0) * u(rng), 300 * (2 * u(rng) - 1), kRimZ + 40 + 200 * u(rng));
  }
};

SideSearch search() {
  SideSearch q;
  q.up = Eigen::Vector3d(0, 0, -1);
  q.axis = Eigen::Vector3d::UnitX(), q.across = Eigen::Vector3d::UnitY();
  q.dir = 1, q.from = 0, q.across_lo = -300, q.across_hi = 300;
  q.rim_height = -kRimZ, q.tol = 5;
  return q;
}

}  // namespace

TEST(RimStrip, FindsTheInnerEdgeOfTheStripAcross) {
  Samples a;
  a.below(0, 600);
  a.strip(400, 10, -290, 290);
  a.strip(-10, 10, -290, 290);  // the known side itself, behind `from`: not beyond
  const std::optional<double> found = rim_strip_beyond(a.s, search());
  ASSERT_TRUE(found);
  EXPECT_NEAR(*found, 400.0, 4.0);
  // Looking the other way from x = 600, the same strip's inner edge is its far side.
  SideSearch back = search();
  back.dir = -1, back.from = 600;
  const std::optional<double> other = rim_strip_beyond(a.s, back);
  ASSERT_TRUE(other);
  EXPECT_NEAR(*other, 600.0 - 410.0, 4.0);
}

TEST(RimStrip, TheNearerOfTwoStrips) {
  Samples a;
  a.below(0, 800);
  a.strip(520, 10, -290, 290);
  a.strip(250, 10, -250, 280);
  const std::optional<double> found = rim_strip_beyond(a.s, search());
  ASSERT_TRUE(found);
  EXPECT_NEAR(*found, 250.0, 4.0);
}

TEST(RimStrip, NothingButAStripAcrossTheFrame) {
  {  // a level sheet of parts at the rim's height (a bin filled to the brim)
    Samples a;
    for (double x = 30; x < 500; x += 6)
      for (double y = -290; y <= 290; y += 6) a.add(x, y, kRimZ);
    EXPECT_FALSE(rim_strip_beyond(a.s, search()));
  }
  {  // a side of the rim along the axis: one place across
    Samples a;
    a.below(0, 600);
    for (double x = 30; x < 500; x += 3) a.add(x, -295, kRimZ), a.add(x, -291, kRimZ);
    EXPECT_FALSE(rim_strip_beyond(a.s, search()));
  }
  {  // a piece of something at the rim's height, a third of the width
    Samples a;
    a.below(0, 600);
    a.strip(300, 10, -100, 90);
    EXPECT_FALSE(rim_strip_beyond(a.s, search()));
  }
  {  // a strip within 4 tolerances of the edge known is that edge's own rim
    Samples a;
    a.below(0, 600);
    a.strip(-5, 10, -290, 290);
    EXPECT_FALSE(rim_strip_beyond(a.s, search()));
  }
}

// A mesh wall at x = 400 (vertical bars every 40 mm across, horizontal ones every 60 mm of
// height, 4 mm thick) from the floor (z = 1300) up to 20 mm under the rim, the floor inside with
// parts on it, and beyond the wall the ground 50 mm under the floor, seen through the mesh.
Samples mesh_wall(double wall_top_z, double parts_high = 60) {
  Samples a;
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 4000; ++i)
    a.add(400 * u(a.rng), 580 * u(a.rng) - 290, 1300 - parts_high * u(a.rng) * (u(a.rng) < 0.3));
  for (double y = -290; y <= 290; y += 40)
    for (double z = wall_top_z; z <= 1300; z += 4)
      for (double x = 400; x <= 404; x += 2) a.add(x, y + 2 * u(a.rng), z);
  for (double z = 1300; z >= wall_top_z; z -= 60)
    for (double y = -290; y <= 290; y += 4)
      for (double x = 400; x <= 404; x += 2) a.add(x, y, z);
  for (int i = 0; i < 4000; ++i) a.add(404 + 300 * u(a.rng), 580 * u(a.rng) - 290, 1350);
  return a;
}

TEST(Wall, FindsTheInnerFaceOfAMeshWall) {
  const Samples a = mesh_wall(kRimZ + 20);
  const std::optional<double> found = wall_beyond(a.s, search());
  ASSERT_TRUE(found);
  EXPECT_NEAR(*found, 400.0, 4.0);
}

TEST(Wall, NotTheGroundNorAKerb) {
  Samples ground;
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 6000; ++i) ground.add(600 * u(ground.rng), 580 * u(ground.rng) - 290, 1300);
  for (int i = 0; i < 4000; ++i)
    ground.add(400 + 300 * u(ground.rng), 580 * u(ground.rng) - 290, 1350);
  EXPECT_FALSE(wall_beyond(ground.s, search()));
  // A wall only 40 mm high on a bare floor: a kerb between the floor and the ground, not a
  // bin's wall.
  const Samples kerb = mesh_wall(1260, 0);
  Samples with_rim = kerb;
  with_rim.add(0, 0, kRimZ);  // heights from the floor up to the rim's
  EXPECT_FALSE(wall_beyond(with_rim.s, search()));
}

TEST(RimStrip, DegenerateInput) {
  EXPECT_FALSE(rim_strip_beyond(PlaneSamples{}, search()));
  Samples a;
  a.strip(400, 10, -290, 290);
  SideSearch q = search();
  q.across_hi = q.across_lo;  // no extent across
  EXPECT_FALSE(rim_strip_beyond(a.s, q));
  q = search();
  q.tol = 0;
  EXPECT_FALSE(rim_strip_beyond(a.s, q));
  Samples few;
  few.strip(400, 0, -290, -200);  // a handful of samples
  EXPECT_FALSE(rim_strip_beyond(few.s, search()));
  EXPECT_FALSE(wall_beyond(PlaneSamples{}, search()));
  EXPECT_FALSE(wall_beyond(few.s, search()));  // nothing below the rim
}
