// The built-in parts: closed, outward, true normals at sharp edges, their nominal diameters,
// centred, and their recorded symmetries really map them onto themselves; the plate is thin,
// holed and without symmetry, the shaft long and round.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <set>

#include "host/core/error.hpp"
#include "host/core/diameter.hpp"
#include "host/app/options/model_options.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "host/core/mesh_geometry.hpp"
#include "host/core/mesh_topology.hpp"
#include "synth/parts/builtin_parts.hpp"

namespace binpick {
namespace {

// Distance from p to the triangle a b c (closest point by regions, Ericson's Real-Time
// Collision Detection 5.1.5).
double distance_to_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denominator = 1 / (va + vb + vc);
  return (p - (a + ab * vb * denominator + ac * vc * denominator)).norm();
}

// How far the rigid motion x -> R x + t moves the part's surface off itself: the largest
// distance from a moved vertex to the part's triangles that face the way the vertex's moved
// normal does (within 30 degrees). About 0 for a symmetry; a thin plate's moved vertices all
// lie near its faces, so the normals must agree too, or a half turn of a plate would look
// like a symmetry whatever its holes.
double largest_offset(const Mesh& mesh, const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  double largest = 0;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const Eigen::Vector3d p = R * mesh.positions[v].cast<double>() + t;
    const Eigen::Vector3d n = R * mesh.normals[v].cast<double>();
    double nearest = INFINITY;
    for (const auto& tri : mesh.triangles) {
      const Eigen::Vector3d a = mesh.positions[tri[0]].cast<double>(),
                            b = mesh.positions[tri[1]].cast<double>(),
                            c = mesh.positions[tri[2]].cast<double>();
      if ((b - a).cross(c - a).normalized().dot(n) < std::cos(M_PI / 6)) continue;
      nearest = std::min(nearest, distance_to_triangle(p, a, b, c));
    }
    largest = std::max(largest, nearest);
  }
  return largest;
}

// Rotation by angle about the axis through offset, as x -> R x + t.
std::pair<Eigen::Matrix3d, Eigen::Vector3d> rotation_about(const ContinuousSymmetry& axis,
                                                           double angle) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, axis.axis.normalized()).toRotationMatrix();
  return {R, axis.offset - R * axis.offset};
}

// The bounding box's extents, smallest first.
std::array<float, 3> sorted_extents(const Mesh& mesh) {
  const Eigen::Vector3f size = bounding_box(mesh.positions).size();
  std::array<float, 3> e{size.x(), size.y(), size.z()};
  std::sort(e.begin(), e.end());
  return e;
}

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
  EXPECT_NEAR(exact_diameter(mesh.positions), builtin_part_nominal_diameter(GetParam()), 1e-4);
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
  // A continuous symmetry, turned by odd angles: every vertex stays on the surface, up to the
  // sagitta of the facets (under 0.003 of the diameter at 48 samples around).
  for (const auto& axis : symmetries.continuous) {
    for (double angle : {0.3, 1.9, 4.4}) {
      const auto [R, t] = rotation_about(axis, angle);
      EXPECT_LT(largest_offset(mesh, R, t), 0.003 * exact_diameter(mesh.positions))
          << "turned by " << angle << " about " << axis.axis.transpose() << " through "
          << axis.offset.transpose();
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllParts, BuiltinPart, testing::ValuesIn(builtin_part_names()),
                         [](const auto& info) { return info.param; });

TEST(BuiltinParts, NamesAndDescriptions) {
  const auto names = builtin_part_names();
  EXPECT_EQ(names, (std::vector<std::string>{"bracket", "bolt", "tee", "plate", "shaft"}));
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
  EXPECT_TRUE(builtin_part_symmetries("plate").empty());
  const PartSymmetries shaft = builtin_part_symmetries("shaft");  // its axis, nothing else
  EXPECT_EQ(shaft.continuous.size(), 1u);
  EXPECT_TRUE(shaft.discrete.empty());
}

TEST(BuiltinParts, NominalDiameters) {
  for (const auto& name : {"bracket", "bolt", "tee", "shaft"})
    EXPECT_EQ(builtin_part_nominal_diameter(name), builtin_part_diameter) << name;
  EXPECT_EQ(builtin_part_nominal_diameter("plate"), 120);
  EXPECT_THROW(builtin_part_nominal_diameter("sprocket"), InputError);
}

TEST(Plate, IsThinSheetAbout120Across) {
  const Mesh plate = make_builtin_part("plate");
  const auto extents = sorted_extents(plate);
  EXPECT_LT(extents[0], 2.0f);  // sheet metal
  EXPECT_GT(extents[0], 1.0f);
  EXPECT_NEAR(extents[2], 110, 2);
  EXPECT_NEAR(extents[1], 50, 1);
  EXPECT_NEAR(exact_diameter(plate.positions), 120, 1e-3);
}

TEST(Plate, HasThreeThroughHoles) {
  // Welded by position, a closed surface of genus g has V - E + F = 2 - 2g; each hole through
  // the plate adds one to the genus.
  const Mesh plate = make_builtin_part("plate");
  const auto weld = first_index_at_same_position(plate.positions);
  std::set<std::uint32_t> vertices(weld.begin(), weld.end());
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const auto& t : plate.triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = weld[t[k]], b = weld[t[(k + 1) % 3]];
      edges.insert(std::minmax(a, b));
    }
  }
  const long euler = static_cast<long>(vertices.size()) - static_cast<long>(edges.size()) +
                     static_cast<long>(plate.triangles.size());
  EXPECT_EQ(euler, 2 - 2 * 3);
}

TEST(Plate, NoHalfTurnMapsItOntoItself) {
  const Mesh plate = make_builtin_part("plate");
  const Eigen::Vector3f size = bounding_box(plate.positions).size();
  int thin = 0;
  size.minCoeff(&thin);
  // The check itself: the mirror through the mid-plane does map the plate onto itself.
  Eigen::Matrix3d mirror = Eigen::Matrix3d::Identity();
  mirror(thin, thin) = -1;
  EXPECT_LT(largest_offset(plate, mirror, Eigen::Vector3d::Zero()), 1e-3);
  // A half turn about any axis of the plate moves some edge of a hole (or the rim) by more than
  // 5 mm off every wall that faces the same way.
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(M_PI, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
    EXPECT_GT(largest_offset(plate, R, Eigen::Vector3d::Zero()), 5) << "about axis " << axis;
  }
}

TEST(Shaft, IsFourToFiveTimesAsLongAsWide) {
  const auto extents = sorted_extents(make_builtin_part("shaft"));
  EXPECT_NEAR(extents[0], extents[1], 1e-4);  // round
  EXPECT_GE(extents[2] / extents[1], 4.0f);
  EXPECT_LE(extents[2] / extents[1], 5.0f);
}

TEST(Shaft, TurnsAboutItsLongAxisOnly) {
  const Mesh shaft = make_builtin_part("shaft");
  const ContinuousSymmetry axis = builtin_part_symmetries("shaft").continuous.at(0);
  const Eigen::Vector3f size = bounding_box(shaft.positions).size();
  int longest = 0;
  size.maxCoeff(&longest);
  EXPECT_NEAR(std::abs(axis.axis.normalized()[longest]), 1, 1e-12);
  const Eigen::Vector3d a = axis.axis.normalized();
  EXPECT_LT((axis.offset - axis.offset.dot(a) * a).norm(), 1e-6) << "off the centre line";
  // The turns about the axis are checked by SymmetriesMapTheSurfaceOntoItself; the ends differ,
  // so a half turn about any axis across it is no symmetry.
  for (int across = 0; across < 3; ++across) {
    if (across == longest) continue;
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(M_PI, Eigen::Vector3d::Unit(across)).toRotationMatrix();
    EXPECT_GT(largest_offset(shaft, R, Eigen::Vector3d::Zero()), 5) << "about axis " << across;
  }
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
