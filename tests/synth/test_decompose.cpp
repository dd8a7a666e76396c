// Convex decomposition with HACD and its on-disk cache.
#include <Eigen/Eigenvalues>
#include <LinearMath/btConvexHullComputer.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "host/core/error.hpp"
#include "synth/decompose/convex_cache.hpp"
#include "synth/decompose/decompose.hpp"
#include "synth/parts/builtin_parts.hpp"
#include "tests/support/test_meshes.hpp"

namespace binpick {
namespace {

using test::box;
using test::l_bracket;
using test::torus;

// Every triangle with its own three vertices, as STL files and per-face normals give them.
Mesh split_vertices(const Mesh& mesh) {
  Mesh split;
  for (const auto& t : mesh.triangles) {
    const auto base = static_cast<std::uint32_t>(split.positions.size());
    for (std::uint32_t i : t) split.positions.push_back(mesh.positions[i]);
    split.triangles.push_back({base, base + 1, base + 2});
  }
  return split;
}

DecomposeOptions uncached() {
  DecomposeOptions o;
  o.use_cache = false;
  return o;
}

// Largest distance of a vertex inside the convex hull of all the hull's vertices: 0 when the
// vertices are in convex position (each one on the hull's boundary).
double deepest_interior_vertex(const ConvexHull& hull) {
  btConvexHullComputer computer;
  computer.compute(hull.vertices.data()->data(), sizeof(Eigen::Vector3f),
                   static_cast<int>(hull.vertices.size()), 0, 0);
  std::vector<std::pair<btVector3, btScalar>> planes;
  for (int f = 0; f < computer.faces.size(); ++f) {
    const auto* e = &computer.edges[computer.faces[f]];
    const btVector3 a = computer.vertices[e->getSourceVertex()];
    const btVector3 b = computer.vertices[e->getTargetVertex()];
    const btVector3 c = computer.vertices[e->getNextEdgeOfFace()->getTargetVertex()];
    const btVector3 n = (b - a).cross(c - a).normalized();
    planes.emplace_back(n, n.dot(a));
  }
  double deepest = 0;
  for (const auto& v : hull.vertices) {
    double outside = -std::numeric_limits<double>::infinity();  // distance to nearest face
    for (const auto& [n, d] : planes)
      outside = std::max(outside, double(n.dot(btVector3(v.x(), v.y(), v.z())) - d));
    deepest = std::max(deepest, -outside);
  }
  return deepest;
}

std::pair<Eigen::Vector3f, Eigen::Vector3f> bounds(const std::vector<Eigen::Vector3f>& points) {
  Eigen::Vector3f lo = points.front(), hi = lo;
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo, hi};
}

// The smallest extent of the points along their principal axes.
float smallest_extent(const std::vector<Eigen::Vector3f>& points) {
  Eigen::Vector3f mean = Eigen::Vector3f::Zero();
  for (const auto& p : points) mean += p;
  mean /= float(points.size());
  Eigen::Matrix3f covariance = Eigen::Matrix3f::Zero();
  for (const auto& p : points) covariance += (p - mean) * (p - mean).transpose();
  const Eigen::Matrix3f axes = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f>(covariance).eigenvectors();
  std::vector<Eigen::Vector3f> along;
  for (const auto& p : points) along.push_back(axes.transpose() * p);
  const auto [lo, hi] = bounds(along);
  return (hi - lo).minCoeff();
}

std::filesystem::path fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("binpick-test-decompose-" + std::to_string(::getpid()) + "-" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

void expect_same(const ConvexParts& a, const ConvexParts& b) {
  ASSERT_EQ(a.hulls.size(), b.hulls.size());
  for (std::size_t h = 0; h < a.hulls.size(); ++h)
    EXPECT_EQ(a.hulls[h].vertices, b.hulls[h].vertices) << "hull " << h;
}

class DecomposePart : public ::testing::TestWithParam<int> {
 protected:
  Mesh part() const {
    switch (GetParam()) {
      case 0:
        return l_bracket();
      case 1:
        return box({30, 20, 10});
      default:
        return torus();
    }
  }
};

TEST_P(DecomposePart, HullsAreConvexAndSpanTheMesh) {
  const Mesh mesh = part();
  const ConvexParts parts = decompose_convex(mesh, uncached());
  ASSERT_FALSE(parts.hulls.empty());
  std::vector<Eigen::Vector3f> all;
  for (const auto& hull : parts.hulls) {
    ASSERT_GE(hull.vertices.size(), 4u);
    EXPECT_LT(deepest_interior_vertex(hull), 1e-3);
    all.insert(all.end(), hull.vertices.begin(), hull.vertices.end());
  }
  const auto [lo, hi] = bounds(all);
  const auto [mesh_lo, mesh_hi] = bounds(mesh.positions);
  const float tolerance = 0.01f * (mesh_hi - mesh_lo).norm();
  EXPECT_LT((lo - mesh_lo).cwiseAbs().maxCoeff(), tolerance);
  EXPECT_LT((hi - mesh_hi).cwiseAbs().maxCoeff(), tolerance);
}

INSTANTIATE_TEST_SUITE_P(Parts, DecomposePart, ::testing::Values(0, 1, 2));

TEST(Decompose, ConcavePartsGiveSeveralHulls) {
  EXPECT_GE(decompose_convex(l_bracket(), uncached()).hulls.size(), 2u);
  EXPECT_GE(decompose_convex(torus(), uncached()).hulls.size(),
            4u);  // one hull would fill the hole
}

TEST(Decompose, SameHullsAtAnyScale) {
  // HACD's concavity depends on the scale (docs/synthesis.md); the normalisation must hide that.
  // A power of two scales every float exactly: HACD must then see the very same input. (At
  // other factors rounding alone can tip HACD's greedy merging by one hull.)
  const float scale = 128.0f;
  Mesh big = torus();
  for (auto& p : big.positions) p *= scale;
  const auto small_parts = decompose_convex(torus(), uncached());
  const auto big_parts = decompose_convex(big, uncached());
  ASSERT_EQ(small_parts.hulls.size(), big_parts.hulls.size());
  for (std::size_t h = 0; h < small_parts.hulls.size(); ++h) {
    const auto& small = small_parts.hulls[h].vertices;
    const auto& large = big_parts.hulls[h].vertices;
    ASSERT_EQ(small.size(), large.size());
    for (std::size_t v = 0; v < small.size(); ++v)
      EXPECT_LT((small[v] * scale - large[v]).norm(), 1e-3f * scale);
  }
}

// HACD returns some clusters of the built-in bracket (the faces around its holes) as flat
// patches; they must not reach the physics, whose step shrinks with the thinnest hull.
TEST(Decompose, NoFlatHulls) {
  const Mesh bracket = make_builtin_part("bracket");
  const auto [lo, hi] = bounds(bracket.positions);
  const float diagonal = (hi - lo).norm();
  std::vector<Eigen::Vector3f> all;
  for (const auto& hull : decompose_convex(bracket, uncached()).hulls) {
    EXPECT_GE(smallest_extent(hull.vertices), 0.01f * diagonal);
    all.insert(all.end(), hull.vertices.begin(), hull.vertices.end());
  }
  // What is left still spans the part.
  const auto [hulls_lo, hulls_hi] = bounds(all);
  EXPECT_LT((hulls_lo - lo).cwiseAbs().maxCoeff(), 0.01f * diagonal);
  EXPECT_LT((hulls_hi - hi).cwiseAbs().maxCoeff(), 0.01f * diagonal);
}

TEST(Decompose, SplitVerticesAreWelded) {
  const auto welded = decompose_convex(torus(), uncached());
  const auto split = decompose_convex(split_vertices(torus()), uncached());
  EXPECT_EQ(welded.hulls.size(), split.hulls.size());
}

TEST(Decompose, BadMeshesAreInputErrors) {
  EXPECT_THROW(decompose_convex(Mesh{}, uncached()), InputError);
  Mesh out_of_range = box({1, 1, 1});
  out_of_range.triangles[0][1] = 8;
  EXPECT_THROW(decompose_convex(out_of_range, uncached()), InputError);
  Mesh not_finite = box({1, 1, 1});
  not_finite.positions[3].x() = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(decompose_convex(not_finite, uncached()), InputError);
  Mesh flat = box({1, 1, 1});
  for (auto& p : flat.positions) p = Eigen::Vector3f::Zero();
  EXPECT_THROW(decompose_convex(flat, uncached()), InputError);
}

TEST(DecomposeCache, HitReturnsTheStoredHulls) {
  DecomposeOptions options;
  options.cache_dir = fresh_dir("hit");
  const Mesh mesh = l_bracket();
  const ConvexParts computed = decompose_convex(mesh, options);
  const auto file = cache_file(options.cache_dir, decomposition_key(mesh, options));
  ASSERT_TRUE(std::filesystem::exists(file));
  expect_same(decompose_convex(mesh, options), computed);

  // Prove the second call reads the file: store something HACD would never produce.
  ConvexParts marker;
  marker.hulls.push_back({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}});
  ASSERT_TRUE(write_cached_parts(file, decomposition_key(mesh, options), marker));
  expect_same(decompose_convex(mesh, options), marker);
  std::filesystem::remove_all(options.cache_dir);
}

TEST(DecomposeCache, CorruptFilesAreRecomputed) {
  DecomposeOptions options;
  options.cache_dir = fresh_dir("corrupt");
  const Mesh mesh = l_bracket();
  const ConvexParts computed = decompose_convex(mesh, options);
  const auto file = cache_file(options.cache_dir, decomposition_key(mesh, options));
  const auto size = std::filesystem::file_size(file);

  const auto corrupt_and_check = [&](auto corrupt) {
    corrupt();
    EXPECT_FALSE(read_cached_parts(file, decomposition_key(mesh, options)).has_value());
    expect_same(decompose_convex(mesh, options), computed);
    EXPECT_TRUE(
        read_cached_parts(file, decomposition_key(mesh, options)).has_value());  // rewritten
  };
  corrupt_and_check([&] { std::filesystem::resize_file(file, size / 2); });
  corrupt_and_check([&] { std::filesystem::resize_file(file, 3); });
  corrupt_and_check([&] { std::ofstream(file, std::ios::binary | std::ios::trunc); });
  corrupt_and_check([&] {
    std::fstream f(file, std::ios::binary | std::ios::in | std::ios::out);
    f.seekp(static_cast<std::streamoff>(size / 2));
    f.put('\x7f');
  });
  corrupt_and_check([&] {
    std::ofstream(file, std::ios::binary | std::ios::trunc) << std::string(size, '\xff');
  });
  std::filesystem::remove_all(options.cache_dir);
}

TEST(DecomposeCache, KeyDependsOnMeshAndOptions) {
  const Mesh mesh = l_bracket();
  const DecomposeOptions options;
  Mesh moved = mesh;
  moved.positions[0].x() += 0.001f;
  DecomposeOptions finer = options;
  finer.concavity *= 0.5;
  DecomposeOptions elsewhere = options;
  elsewhere.cache_dir = "/somewhere/else";
  EXPECT_NE(decomposition_key(mesh, options), decomposition_key(moved, options));
  EXPECT_NE(decomposition_key(mesh, options), decomposition_key(mesh, finer));
  EXPECT_EQ(decomposition_key(mesh, options), decomposition_key(mesh, elsewhere));
}

// Sets an environment variable for one scope and puts the old value back.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    value ? ::setenv(name, value, 1) : ::unsetenv(name);
  }
  ~ScopedEnv() { old_ ? ::setenv(name_, old_->c_str(), 1) : ::unsetenv(name_); }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(DecomposeCache, DirectoryFromArgumentThenEnvironment) {
  {
    ScopedEnv cache("BINPICK_CACHE_DIR", "/tmp/from-env");
    EXPECT_EQ(resolve_cache_dir(""), std::filesystem::path("/tmp/from-env"));
    EXPECT_EQ(resolve_cache_dir("/tmp/from-arg"), std::filesystem::path("/tmp/from-arg"));
  }
  ScopedEnv cache("BINPICK_CACHE_DIR", nullptr);
  ScopedEnv xdg("XDG_CACHE_HOME", "/tmp/xdg");
  EXPECT_EQ(resolve_cache_dir(""), std::filesystem::path("/tmp/xdg/binpick"));
  ScopedEnv no_xdg("XDG_CACHE_HOME", nullptr);
  ScopedEnv home("HOME", "/tmp/home");
  EXPECT_EQ(resolve_cache_dir(""), std::filesystem::path("/tmp/home/.cache/binpick"));
}

}  // namespace
}  // namespace binpick
