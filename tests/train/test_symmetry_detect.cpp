// Symmetries found on a mesh (host/train/symmetry_detect.cpp) against the ones stated for the
// built-in parts and for simple solids, compared as sets of rigid motions (not by order):
// rotations within 1 degree, the images of the centroid within 1 % of the diameter; for a
// continuous axis, the axis' direction and line, and a discrete symmetry by where it sends the
// axis (the turn about the axis is free). Perturbed meshes must come out without symmetry.
// Also the one-line description `binpick train` prints.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Geometry>

#include "host/core/diameter.hpp"
#include "host/core/error.hpp"
#include "host/train/symmetry_describe.hpp"
#include "host/train/symmetry_detect.hpp"
#include "synth/parts/builtin_parts.hpp"
#include "tests/support/test_meshes.hpp"

using namespace binpick;

namespace {

constexpr double kPi = std::numbers::pi;

double rotation_deg(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  const Eigen::Quaterniond a(A), b(B);
  return 2 * std::acos(std::min(1.0, std::fabs(a.dot(b)))) * 180 / kPi;
}

Eigen::Vector3d centre_of(const Mesh& m) {
  Eigen::Vector3d lo = m.positions[0].cast<double>(), hi = lo;
  for (const auto& p : m.positions) {
    lo = lo.cwiseMin(p.cast<double>());
    hi = hi.cwiseMax(p.cast<double>());
  }
  return (lo + hi) / 2;
}

// Empty if `found` equals `want` for the mesh (see the file comment), else what differs.
std::string compare(const PartSymmetries& found, const PartSymmetries& want, const Mesh& mesh) {
  const double d = exact_diameter(mesh.positions), tol = 0.01 * d;
  const Eigen::Vector3d c = centre_of(mesh);
  std::string why;
  if (found.continuous.size() != want.continuous.size())
    return "continuous: found " + std::to_string(found.continuous.size()) + ", want " +
           std::to_string(want.continuous.size());
  if (found.discrete.size() != want.discrete.size())
    return "discrete: found " + std::to_string(found.discrete.size()) + ", want " +
           std::to_string(want.discrete.size());
  for (std::size_t k = 0; k < want.continuous.size(); ++k) {
    const auto& w = want.continuous[k];
    bool matched = false;
    for (const auto& f : found.continuous) {
      const Eigen::Vector3d a = w.axis.normalized();
      const bool parallel = std::fabs(f.axis.normalized().dot(a)) > std::cos(kPi / 180);
      const Eigen::Vector3d off = f.offset - w.offset;
      matched |= parallel && (off - off.dot(a) * a).norm() < tol;
    }
    if (!matched) why += "continuous axis " + std::to_string(k) + " not found; ";
  }
  for (std::size_t k = 0; k < want.discrete.size(); ++k) {
    const Eigen::Matrix4d& w = want.discrete[k];
    bool matched = false;
    for (const Eigen::Matrix4d& f : found.discrete) {
      const Eigen::Matrix3d Rf = f.topLeftCorner<3, 3>(), Rw = w.topLeftCorner<3, 3>();
      const Eigen::Vector3d cf = Rf * c + f.topRightCorner<3, 1>();
      const Eigen::Vector3d cw = Rw * c + w.topRightCorner<3, 1>();
      if (want.continuous.empty()) {
        matched |= rotation_deg(Rf, Rw) < 1.0 && (cf - cw).norm() < tol;
      } else {
        const Eigen::Vector3d a = want.continuous.front().axis.normalized();
        matched |= (Rf * a - Rw * a).norm() < std::sin(kPi / 180) && (cf - cw).norm() < tol;
      }
    }
    if (!matched) why += "discrete " + std::to_string(k) + " not found; ";
  }
  return why;
}

Eigen::Matrix4d rigid(const Eigen::Matrix3d& R,
                      const Eigen::Vector3d& t = Eigen::Vector3d::Zero()) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = R;
  m.topRightCorner<3, 1>() = t;
  return m;
}

// Rotation by angle about `axis` through `point`, as a 4x4.
Eigen::Matrix4d turn(const Eigen::Vector3d& axis, double angle, const Eigen::Vector3d& point) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  return rigid(R, point - R * point);
}

// A right prism over a regular n-gon of circumradius r (a vertex on +x), z from 0 to h,
// outward and counter-clockwise; with r_alt > 0, over a 2n-gon whose vertices alternate between
// r and r_alt (a gear of n teeth).
Mesh prism(int n, float r, float h, float r_alt = 0) {
  Mesh m;
  const int corners = r_alt > 0 ? 2 * n : n;
  for (float z : {0.0f, h})
    for (int i = 0; i < corners; ++i) {
      const float radius = r_alt > 0 && i % 2 == 1 ? r_alt : r;
      const double a = 2 * kPi * i / corners;
      m.positions.emplace_back(radius * std::cos(a), radius * std::sin(a), z);
    }
  const auto N = std::uint32_t(corners);
  m.positions.emplace_back(0, 0, 0);
  m.positions.emplace_back(0, 0, h);
  for (std::uint32_t i = 0; i < N; ++i) {
    const std::uint32_t j = (i + 1) % N;
    m.triangles.push_back({2 * N, j, i});              // bottom
    m.triangles.push_back({2 * N + 1, N + i, N + j});  // top
    m.triangles.push_back({i, j, N + j});
    m.triangles.push_back({i, N + j, N + i});
  }
  return m;
}

Mesh transformed(Mesh m, const Eigen::Matrix4d& T) {
  for (auto& p : m.positions)
    p = (T.topLeftCorner<3, 3>() * p.cast<double>() + T.topRightCorner<3, 1>()).cast<float>();
  m.normals.clear();
  return m;
}

PartSymmetries found_on(const Mesh& mesh, double* ms = nullptr) {
  const auto start = std::chrono::steady_clock::now();
  PartSymmetries s = find_symmetries(mesh);
  if (ms)
    *ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return s;
}

// The dihedral group of an n-gon prism about z through centre: n - 1 turns about z and n half
// turns about the axes in the xy plane at multiples of pi / n.
PartSymmetries dihedral(int n, const Eigen::Vector3d& centre) {
  PartSymmetries d;
  for (int k = 1; k < n; ++k) d.discrete.push_back(turn({0, 0, 1}, 2 * k * kPi / n, centre));
  for (int k = 0; k < n; ++k)
    d.discrete.push_back(turn({std::cos(k * kPi / n), std::sin(k * kPi / n), 0}, kPi, centre));
  return d;
}

}  // namespace

TEST(SymmetryDetect, BuiltinPartsHaveTheirStatedSymmetries) {
  for (const std::string& name : builtin_part_names()) {
    const Mesh mesh = make_builtin_part(name);
    double ms = 0;
    const PartSymmetries found = found_on(mesh, &ms);
    EXPECT_EQ(compare(found, builtin_part_symmetries(name), mesh), "") << name;
    std::printf("%-8s %zu continuous, %zu discrete in %.0f ms\n", name.c_str(),
                found.continuous.size(), found.discrete.size(), ms);
  }
}

TEST(SymmetryDetect, TorusAndCylinderAreRoundAndSwapTheirFaces) {
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  const Eigen::Matrix4d flip = rigid(Eigen::Vector3d(1, -1, -1).asDiagonal());
  const Mesh torus = test::torus();
  EXPECT_EQ(compare(found_on(torus), {{{z, Eigen::Vector3d::Zero()}}, {flip}}, torus), "");
  const Mesh cylinder = prism(96, 10, 30);
  const Eigen::Vector3d mid(0, 0, 15);
  EXPECT_EQ(compare(found_on(cylinder), {{{z, mid}}, {turn({1, 0, 0}, kPi, mid)}}, cylinder), "");
}

TEST(SymmetryDetect, BoxesAndPrisms) {
  // Three unequal sides: the three half turns.
  const Mesh box = test::box({40, 30, 20});
  const Eigen::Vector3d bc(20, 15, 10);
  PartSymmetries d2;
  for (const Eigen::Vector3d a :
       {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()})
    d2.discrete.push_back(turn(a, kPi, bc));
  EXPECT_EQ(compare(found_on(box), d2, box), "");

  // A square prism: two equal moments, the half turns about the diagonals found by the scan.
  const Mesh square = test::box({30, 30, 12});
  const Eigen::Vector3d sc(15, 15, 6);
  EXPECT_EQ(compare(found_on(square), dihedral(4, sc), square), "");

  // A hexagonal prism: sixfold, and six half turns (through vertices and through edge middles).
  const Mesh hex = prism(6, 15, 10);
  const Eigen::Vector3d hc(0, 0, 5);
  EXPECT_EQ(compare(found_on(hex), dihedral(6, hc), hex), "");

  // A gear of 14 teeth on a round shaft standing on one face (no half turn swaps its ends,
  // which would generate the fourteen turns from two half turns): fourteenfold. With orders up
  // to 12 it came out sevenfold; with the first turn of each order alone, "fifteenfold" with
  // two elements (a 24-degree turn moves the teeth within the test's tolerance, 48 does not).
  Mesh gear = prism(14, 15, 10, 12.5f);
  Mesh boss = prism(28, 6, 40);
  const auto base = std::uint32_t(gear.positions.size());
  for (const auto& p : boss.positions) gear.positions.push_back(p + Eigen::Vector3f(0, 0, 10));
  for (const auto& t : boss.triangles) gear.triangles.push_back({base + t[0], base + t[1], base + t[2]});
  PartSymmetries c14;
  for (int k = 1; k < 14; ++k) c14.discrete.push_back(turn({0, 0, 1}, 2 * k * kPi / 14, hc));
  EXPECT_EQ(compare(found_on(gear), c14, gear), "");

  // A cube: three equal moments; the 23 rotations of the octahedral group. Also turned off the
  // axes and with its corners moved by up to 0.1 mm (axes from faces and vertices, off by a
  // little: the group must still close), and a regular tetrahedron (12 rotations).
  const Mesh cube = test::box({30, 30, 30});
  const PartSymmetries found = found_on(cube);
  EXPECT_TRUE(found.continuous.empty());
  EXPECT_EQ(found.discrete.size(), 23u);
  Mesh turned = transformed(cube, turn({1, 2, 3}, 0.7, Eigen::Vector3d::Zero()));
  std::mt19937 rng(1);
  for (auto& p : turned.positions)
    p += Eigen::Vector3f(float(rng() % 201) - 100, float(rng() % 201) - 100,
                         float(rng() % 201) - 100) *
         1e-3f;
  EXPECT_EQ(found_on(turned).discrete.size(), 23u);
  Mesh tetra;
  tetra.positions = {{15, 15, 15}, {15, -15, -15}, {-15, 15, -15}, {-15, -15, 15}};
  tetra.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  EXPECT_EQ(found_on(tetra).discrete.size(), 11u);
}

// Whether the discrete symmetries found are a group: the product of any two, and the inverse
// of each, is the identity or one of them (rotations within 1 degree, the centroid's image
// within 1 % of the diameter). Empty if so, else the first product missing.
std::string not_a_group(const PartSymmetries& s, const Mesh& mesh) {
  const double tol = 0.01 * exact_diameter(mesh.positions);
  const Eigen::Vector3d c = centre_of(mesh);
  std::vector<Eigen::Matrix4d> all = s.discrete;
  all.push_back(Eigen::Matrix4d::Identity());
  const auto member = [&](const Eigen::Matrix4d& m) {
    return std::any_of(all.begin(), all.end(), [&](const Eigen::Matrix4d& e) {
      const Eigen::Vector3d cm = m.topLeftCorner<3, 3>() * c + m.topRightCorner<3, 1>();
      const Eigen::Vector3d ce = e.topLeftCorner<3, 3>() * c + e.topRightCorner<3, 1>();
      return rotation_deg(m.topLeftCorner<3, 3>(), e.topLeftCorner<3, 3>()) < 1.0 &&
             (cm - ce).norm() < tol;
    });
  };
  for (std::size_t i = 0; i < s.discrete.size(); ++i) {
    if (!member(s.discrete[i].inverse())) return "the inverse of " + std::to_string(i);
    for (std::size_t j = 0; j < s.discrete.size(); ++j)
      if (!member(s.discrete[i] * s.discrete[j]))
        return std::to_string(i) + " x " + std::to_string(j);
  }
  return "";
}

// A cap screw along z: a round shank (radius 4, 0 to 40 mm) and head (radius 6.5, 40 to 48)
// with a hexagonal socket `flats` across and 4 deep in the head's top: the socket's outline
// runs through the top face, its walls face in, and its floor faces up. 48 points a loop (the
// hexagon's sides 8 points each), so the top is a strip between two loops.
Mesh cap_screw(float flats) {
  Mesh m;
  const int n = 48;
  const auto loop = [&](float z, bool hex, float radius) {
    const auto first = std::uint32_t(m.positions.size());
    for (int i = 0; i < n; ++i) {
      if (!hex) {
        const double a = 2 * kPi * i / n;
        m.positions.emplace_back(radius * std::cos(a), radius * std::sin(a), z);
        continue;
      }
      const double r = flats / std::sqrt(3.0);
      const int side = i / 8, step = i % 8;
      const double a0 = kPi / 3 * side, a1 = kPi / 3 * (side + 1), t = step / 8.0;
      m.positions.emplace_back(r * ((1 - t) * std::cos(a0) + t * std::cos(a1)),
                               r * ((1 - t) * std::sin(a0) + t * std::sin(a1)), z);
    }
    return first;
  };
  // A strip between loops a and b (same count), wound so that its normal is the right-hand
  // one of (a[i] -> a[i+1], a[i] -> b[i]).
  const auto strip = [&](std::uint32_t a, std::uint32_t b) {
    for (std::uint32_t i = 0; i < std::uint32_t(n); ++i) {
      const std::uint32_t j = (i + 1) % n;
      m.triangles.push_back({a + i, a + j, b + j});
      m.triangles.push_back({a + i, b + j, b + i});
    }
  };
  const auto fan = [&](std::uint32_t a, float z, bool up) {
    const auto c = std::uint32_t(m.positions.size());
    m.positions.emplace_back(0, 0, z);
    for (std::uint32_t i = 0; i < std::uint32_t(n); ++i) {
      const std::uint32_t j = (i + 1) % n;
      m.triangles.push_back(up ? std::array<std::uint32_t, 3>{c, a + i, a + j}
                               : std::array<std::uint32_t, 3>{c, a + j, a + i});
    }
  };
  const std::uint32_t shank0 = loop(0, false, 4), shank1 = loop(40, false, 4);
  const std::uint32_t head0 = loop(40, false, 6.5f), head1 = loop(48, false, 6.5f);
  const std::uint32_t top = loop(48, true, 0), bottom = loop(44, true, 0);
  fan(shank0, 0, false);
  strip(shank0, shank1);  // the shank's side, facing out
  strip(shank1, head0);   // the head's underside, facing down
  strip(head0, head1);    // the head's side
  strip(head1, top);      // the head's top, a ring around the socket, facing up
  strip(top, bottom);     // the socket's walls, facing in
  fan(bottom, 44, true);  // the socket's floor
  return m;
}

// The cap screw is round about its axis but for its socket: within the test's tolerance (1 %
// of the diameter) many turns nearly pass, and which orders pass depends on the socket's size
// (round, 6, 8, 12 or 24-fold between 5 and 7 mm). What is found must still be a group: with
// only the turns up to a half turn tested, the 6.1 mm socket came out "13-fold" with 9 of its
// 12 turns (and an 8 mm screw of another mesh eightfold with +45 degrees but not -45).
TEST(SymmetryDetect, ANearlyRoundPartHasAGroup) {
  for (float flats : {5.0f, 5.75f, 6.0f, 6.1f, 6.2f, 6.6f, 6.75f, 7.0f}) {
    SCOPED_TRACE(testing::Message() << "socket " << flats);
    const Mesh screw = cap_screw(flats);
    const PartSymmetries found = found_on(screw);  // round (continuous) or n-fold
    EXPECT_EQ(not_a_group(found, screw), "") << describe_symmetries(found);
  }
  // The stated groups of the built-in parts are groups (the check itself).
  for (const char* part : {"bolt", "tee"}) {
    const Mesh m = make_builtin_part(part);
    EXPECT_EQ(not_a_group(builtin_part_symmetries(part), m), "") << part;
  }
}

TEST(SymmetryDetect, FollowsTheMeshFrame) {
  // The bolt moved and turned: its symmetries are the stated ones conjugated, T S T^-1.
  const Eigen::Matrix4d T = turn(Eigen::Vector3d(0.3, -0.5, 0.8), 1.2, Eigen::Vector3d::Zero()) *
                            rigid(Eigen::Matrix3d::Identity(), Eigen::Vector3d(35, -20, 110));
  const Mesh bolt = transformed(make_builtin_part("bolt"), T);
  PartSymmetries want = builtin_part_symmetries("bolt");
  for (auto& m : want.discrete) m = T * m * T.inverse();
  EXPECT_EQ(compare(found_on(bolt), want, bolt), "");

  const Mesh shaft = transformed(make_builtin_part("shaft"), T);
  PartSymmetries round = builtin_part_symmetries("shaft");
  for (auto& s : round.continuous) {
    s.axis = T.topLeftCorner<3, 3>() * s.axis;
    s.offset = T.topLeftCorner<3, 3>() * s.offset + T.topRightCorner<3, 1>();
  }
  EXPECT_EQ(compare(found_on(shaft), round, shaft), "");
}

TEST(SymmetryDetect, PerturbedMeshesHaveNone) {
  // The torus with every vertex moved along its tube normal by up to 1.5 mm (3 % of 52 mm).
  Mesh bumpy = test::torus();
  std::mt19937 rng(5);
  for (std::size_t i = 0; i < bumpy.positions.size(); ++i) {
    Eigen::Vector3f& p = bumpy.positions[i];
    const Eigen::Vector3f ring = 20 * Eigen::Vector3f(p.x(), p.y(), 0).normalized();
    const float shift = (float(rng() % 2001) / 1000.0f - 1.0f) * 1.5f;
    p += shift * (p - ring).normalized();
  }
  EXPECT_TRUE(found_on(bumpy).empty());

  // The 40 x 30 x 20 box with one corner pulled out by 3 mm along each side.
  Mesh box = test::box({40, 30, 20});
  box.positions[7] += Eigen::Vector3f(3, 3, 3);
  EXPECT_TRUE(found_on(box).empty());

  // The hexagonal prism with one vertex pushed in by 2 mm: no sixfold turn, no half turn.
  Mesh hex = prism(6, 15, 10);
  hex.positions[0].x() -= 2;
  EXPECT_TRUE(found_on(hex).empty());

  EXPECT_TRUE(found_on(test::l_bracket()).empty());
}

TEST(SymmetryDetect, DeterministicAndBadMeshes) {
  const Mesh tee = make_builtin_part("tee");
  const PartSymmetries a = find_symmetries(tee), b = find_symmetries(tee);
  ASSERT_EQ(a.discrete.size(), b.discrete.size());
  for (std::size_t k = 0; k < a.discrete.size(); ++k) EXPECT_EQ(a.discrete[k], b.discrete[k]);
  EXPECT_THROW(find_symmetries(Mesh{}), InputError);
  Mesh flat;
  flat.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  flat.triangles = {{0, 1, 2}};
  EXPECT_THROW(find_symmetries(flat), InputError);
}

TEST(SymmetryDescribe, OneLine) {
  EXPECT_EQ(describe_symmetries({}), "none found");
  EXPECT_EQ(describe_symmetries(builtin_part_symmetries("bolt")),
            "5 discrete: 6-fold about (0, 0, 1)");
  EXPECT_EQ(describe_symmetries(found_on(test::torus())),
            "continuous about (0, 0, 1) through (0, 0, 0), ends swapped by a half turn");
  EXPECT_EQ(describe_symmetries(found_on(test::box({40, 30, 20}))),
            "3 discrete: 2-fold about (1, 0, 0), (0, 1, 0), (0, 0, 1)");
  EXPECT_EQ(describe_symmetries(found_on(test::box({30, 30, 12}))),
            "7 discrete: 4-fold about (0, 0, 1); 2-fold about (1, 0, 0), (0.7071, 0.7071, 0), "
            "(0.7071, -0.7071, 0), (0, 1, 0)");
  PartSymmetries sphere;
  sphere.continuous = {{{0, 0, 1}, {0, 0, 0}}, {{1, 0, 0}, {0, 0, 0}}};
  EXPECT_EQ(describe_symmetries(sphere), "any rotation (a sphere)");
}
