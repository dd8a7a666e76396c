// Which side of a mesh is outside (host/core/mesh_orientation.cpp): inside-out, partly turned
// and open meshes, file normals that point inwards, and a loader that repairs an inside-out STL
// so training sees outward normals.
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Geometry>

#include "host/core/mesh_orientation.hpp"
#include "host/core/mesh_topology.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "host/formats/mesh/mesh_writers.hpp"
#include "host/train/surface_sampling.hpp"
#include "tests/support/cli_run.hpp"
#include "tests/support/test_meshes.hpp"

using namespace binpick;

namespace {

double signed_volume(const Mesh& m) {
  double v = 0;
  for (const auto& t : m.triangles)
    v += m.positions[t[0]].cast<double>().dot(
        m.positions[t[1]].cast<double>().cross(m.positions[t[2]].cast<double>()));
  return v / 6;
}

void turn(std::array<std::uint32_t, 3>& t) { std::swap(t[1], t[2]); }

// Surface samples whose normals point away from the part's centre: outward for a convex part.
double outward_fraction(const Mesh& m) {
  const PointCloud s = sample_surface(m, 2000);
  Eigen::Vector3f c = Eigen::Vector3f::Zero();
  for (const auto& p : m.positions) c += p;
  c /= float(m.positions.size());
  int out = 0;
  for (std::size_t i = 0; i < s.points.size(); ++i) out += s.normals[i].dot(s.points[i] - c) > 0;
  return double(out) / double(s.points.size());
}

}  // namespace

TEST(MeshOrientation, OutwardMeshIsLeftAlone) {
  Mesh m = test::l_bracket();
  const Mesh before = m;
  const OrientationReport r = orient_outward(m);
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.closed, 1u);
  EXPECT_EQ(r.made_consistent + r.turned_out + r.undecided, 0u);
  EXPECT_EQ(m.triangles, before.triangles);
}

TEST(MeshOrientation, InsideOutAndPartlyTurnedMeshesAreTurnedOut) {
  Mesh m = test::box({30, 20, 10});
  ASSERT_GT(signed_volume(m), 0);
  for (auto& t : m.triangles) turn(t);
  ASSERT_LT(signed_volume(m), 0);
  ASSERT_LT(outward_fraction(m), 0.01);
  OrientationReport r = orient_outward(m);
  EXPECT_EQ(r.turned_out, m.triangles.size());
  EXPECT_NEAR(signed_volume(m), 6000.0, 1e-6);
  EXPECT_GT(outward_fraction(m), 0.99);

  // A few triangles turned against their neighbours (a careless export): made consistent.
  Mesh mixed = test::l_bracket();
  for (std::size_t i = 0; i < mixed.triangles.size(); i += 5) turn(mixed.triangles[i]);
  ASSERT_FALSE(check_topology(mixed).closed_and_oriented());
  r = orient_outward(mixed);
  EXPECT_GT(r.made_consistent, 0u);
  EXPECT_TRUE(check_topology(mixed).closed_and_oriented());
  EXPECT_GT(signed_volume(mixed), 0);
}

TEST(MeshOrientation, OpenSurfacesFollowFileNormalsOrStayUndecided) {
  // A box with a face missing is nearly closed: its volume still tells inside from outside.
  Mesh open = test::box({30, 20, 10});
  open.triangles.resize(open.triangles.size() - 2);
  for (auto& t : open.triangles) turn(t);
  OrientationReport r = orient_outward(open);
  EXPECT_EQ(r.closed, 0u);
  EXPECT_EQ(r.turned_out, open.triangles.size());
  // A flat sheet has no volume to go by: as wound, unless the file's normals say otherwise.
  Mesh sheet;
  sheet.positions = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {10, 10, 0}};
  sheet.triangles = {{0, 2, 1}, {1, 2, 3}};  // facing -z
  Mesh as_wound = sheet;
  r = orient_outward(as_wound);
  EXPECT_EQ(r.undecided, 2u);
  EXPECT_EQ(as_wound.triangles, sheet.triangles);
  sheet.normals.assign(4, Eigen::Vector3f(0, 0, 1));
  r = orient_outward(sheet);
  EXPECT_EQ(r.turned_out, 2u);
  EXPECT_EQ(r.undecided, 0u);
  EXPECT_FALSE(r.normals_flipped);
}

TEST(MeshOrientation, InwardFileNormalsAreNegated) {
  Mesh m = test::box({30, 20, 10});
  for (const auto& p : m.positions) m.normals.push_back((Eigen::Vector3f(15, 10, 5) - p).normalized());
  const OrientationReport r = orient_outward(m);
  EXPECT_TRUE(r.normals_flipped);
  EXPECT_GT(m.normals[0].dot(m.positions[0] - Eigen::Vector3f(15, 10, 5)), 0);
}

TEST(MeshOrientation, LoaderTurnsAnInsideOutStlAround) {
  const auto dir = test::fresh_temp_dir("orientation");
  Mesh m = test::l_bracket();
  for (auto& t : m.triangles) turn(t);
  write_stl(dir / "inside_out.stl", m);
  const Mesh loaded = load_model((dir / "inside_out.stl").string(), {});
  EXPECT_GT(signed_volume(loaded), 0);
  EXPECT_TRUE(check_topology(loaded).closed_and_oriented());
  std::filesystem::remove_all(dir);
}
