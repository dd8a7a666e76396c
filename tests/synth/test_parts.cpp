// The built-in parts: closed, outward, true normals at sharp edges, 52 mm, centred, and their
// recorded symmetries really map them onto themselves.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "host/core/error.hpp"
#include "host/core/diameter.hpp"
#include "host/app/model_options.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "host/core/mesh_geometry.hpp"
#include "host/core/mesh_topology.hpp"
#include "synth/parts/builtin_parts.hpp"

namespace binpick {
namespace {

class BuiltinPart : public testing::TestWithParam<std::string> {};

TEST_P(BuiltinPart, IsClosedAndConsistentlyOriented) {
  const Mesh mesh = make_builtin_part(GetParam());
  const TopologyReport report = check_topology(mesh);
  EXPECT_EQ(report.boundary_edges, 0u);
  EXPECT_EQ(report.misoriented_edges, 0u);
  EXPECT_EQ(report.non_manifold_edges, 0u);
  EXPECT_EQ(report.degenerate_triangles, 0u);
  EXPECT_GT(signed_volume(mesh), 0) << "triangles must face outwards";
}

TEST_P(BuiltinPart, HasNominalDiameterAndIsCentred) {
  const Mesh mesh = make_builtin_part(GetParam());
  EXPECT_NEAR(exact_diameter(mesh.positions), builtin_part_diameter, 1e-4);
  EXPECT_LT(bounding_box(mesh.positions).center().norm(), 1e-4);
  EXPECT_GT(mesh.triangles.size(), 100u);
}

TEST_P(BuiltinPart, NormalsAreUnitAndNotAveragedAcrossSharpEdges) {
  const Mesh mesh = make_builtin_part(GetParam());
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  for (const auto& n : mesh.normals) ASSERT_NEAR(n.norm(), 1.0f, 1e-5f);
  // Averaging across a 90 degree edge would put a vertex normal 45 degrees off its faces; the
  // facets of the curved surfaces stay within half a sampling step (3.75 degrees).
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3f a = mesh.positions[t[0]], b = mesh.positions[t[1]],
                          c = mesh.positions[t[2]];
    const Eigen::Vector3f face = (b - a).cross(c - a).normalized();
    for (auto v : t) {
      const double degrees =
          std::acos(std::clamp(face.dot(mesh.normals[v]), -1.0f, 1.0f)) * 180 / M_PI;
      ASSERT_LT(degrees, 10.0);
    }
  }
}

TEST_P(BuiltinPart, SymmetriesMapTheSurfaceOntoItself) {
  const Mesh mesh = make_builtin_part(GetParam());
  const PartSymmetries symmetries = builtin_part_symmetries(GetParam());
  for (const auto& m : symmetries.discrete) {
    EXPECT_NEAR((m.topLeftCorner<3, 3>() * m.topLeftCorner<3, 3>().transpose() -
                 Eigen::Matrix3d::Identity())
                    .norm(),
                0, 1e-12);
    for (const auto& p : mesh.positions) {
      const Eigen::Vector3d q = m.topLeftCorner<3, 3>() * p.cast<double>() + m.block<3, 1>(0, 3);
      double nearest = INFINITY;
      for (const auto& r : mesh.positions)
        nearest = std::min(nearest, (r.cast<double>() - q).norm());
      ASSERT_LT(nearest, 1e-3) << "vertex " << p.transpose() << " has no image";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllParts, BuiltinPart, testing::ValuesIn(builtin_part_names()),
                         [](const auto& info) { return info.param; });

TEST(BuiltinParts, NamesAndDescriptions) {
  const auto names = builtin_part_names();
  EXPECT_EQ(names, (std::vector<std::string>{"bracket", "bolt", "tee"}));
  for (const auto& name : names) {
    const std::string description = builtin_part_description(name);
    EXPECT_FALSE(description.empty());
    EXPECT_EQ(description.find_first_of("\t\n"), std::string::npos);
  }
}

TEST(BuiltinParts, KnownSymmetries) {
  EXPECT_TRUE(builtin_part_symmetries("bracket").empty());
  EXPECT_EQ(builtin_part_symmetries("bolt").discrete.size(), 5u);  // hex head: sixfold
  EXPECT_EQ(builtin_part_symmetries("tee").discrete.size(), 1u);   // half turn about the branch
}

TEST(BuiltinParts, UnknownNameListsTheKnownOnes) {
  try {
    make_builtin_part("sprocket");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("sprocket"), std::string::npos);
    for (const auto& name : builtin_part_names()) EXPECT_NE(message.find(name), std::string::npos);
  }
  EXPECT_THROW(cli::load_part({"builtin:sprocket", {}}).mesh, InputError);
}

TEST(BuiltinParts, LoadModelRescalesPartAndSymmetries) {
  ModelOptions options;
  options.diameter = 104;
  const Model model = cli::load_part({"builtin:tee", options});
  EXPECT_NEAR(exact_diameter(model.mesh.positions), 104, 1e-3);
  EXPECT_EQ(model.symmetries.discrete.size(), 1u);
  EXPECT_TRUE(check_topology(model.mesh).closed_and_oriented());
}

}  // namespace
}  // namespace binpick
