// exact_diameter against an O(n^2) brute force, on random clouds (including degenerate ones the
// convex hull has to survive) and on meshes.
#include <gtest/gtest.h>

#include <random>

#include "host/core/diameter.hpp"
#include "synth/parts/builtin_parts.hpp"

namespace binpick {
namespace {

double brute_force_diameter(const std::vector<Eigen::Vector3f>& points) {
  double best = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t j = i + 1; j < points.size(); ++j)
      best = std::max(best, (points[i].cast<double>() - points[j].cast<double>()).norm());
  }
  return best;
}

void expect_matches_brute_force(const std::vector<Eigen::Vector3f>& points) {
  const double expected = brute_force_diameter(points);
  EXPECT_NEAR(exact_diameter(points), expected, 1e-9 * std::max(1.0, expected))
      << points.size() << " points";
}

std::vector<Eigen::Vector3f> random_cloud(std::mt19937& rng, std::size_t n,
                                          Eigen::Vector3f extent) {
  std::normal_distribution<float> gauss;
  std::vector<Eigen::Vector3f> points(n);
  for (auto& p : points)
    p = Eigen::Vector3f(gauss(rng), gauss(rng), gauss(rng)).cwiseProduct(extent);
  return points;
}

TEST(ExactDiameter, EmptyAndSinglePointAreZero) {
  EXPECT_EQ(exact_diameter({}), 0);
  EXPECT_EQ(exact_diameter({Eigen::Vector3f(1, 2, 3)}), 0);
  EXPECT_EQ(exact_diameter(std::vector<Eigen::Vector3f>(100, Eigen::Vector3f(1, 2, 3))), 0);
}

TEST(ExactDiameter, MatchesBruteForceOnRandomClouds) {
  std::mt19937 rng(7);
  for (std::size_t n : {2u, 3u, 10u, 65u, 200u, 1000u, 3000u}) {
    expect_matches_brute_force(random_cloud(rng, n, {1, 1, 1}));
    expect_matches_brute_force(random_cloud(rng, n, {100, 3, 0.5}));  // elongated
  }
}

TEST(ExactDiameter, MatchesBruteForceOnSphereSurface) {
  // Every point is a hull vertex: the worst case for the candidate set.
  std::mt19937 rng(11);
  auto points = random_cloud(rng, 1500, {1, 1, 1});
  for (auto& p : points) p = p.normalized() * 26.0f;
  expect_matches_brute_force(points);
}

TEST(ExactDiameter, MatchesBruteForceOnDegenerateClouds) {
  std::mt19937 rng(3);
  auto planar = random_cloud(rng, 500, {10, 20, 0});  // all z = 0
  auto line = random_cloud(rng, 500, {10, 0, 0});     // all on the x axis
  auto duplicated = random_cloud(rng, 100, {5, 5, 5});
  duplicated.insert(duplicated.end(), duplicated.begin(), duplicated.end());
  for (const auto& cloud : {planar, line, duplicated}) expect_matches_brute_force(cloud);
}

TEST(ExactDiameter, MatchesBruteForceOnBuiltinParts) {
  for (const auto& name : builtin_part_names()) {
    SCOPED_TRACE(name);
    expect_matches_brute_force(make_builtin_part(name).positions);
  }
}

TEST(ExactDiameter, FarFromOriginKeepsPrecision) {
  std::mt19937 rng(5);
  auto points = random_cloud(rng, 300, {2, 2, 2});
  for (auto& p : points) p += Eigen::Vector3f(1000, -2000, 500);
  expect_matches_brute_force(points);
}

}  // namespace
}  // namespace binpick
