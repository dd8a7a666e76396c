#include "host/core/diameter.hpp"

#include <LinearMath/btConvexHullComputer.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace binpick {
namespace {

// Exact farthest pair among candidates. With r_i the distance of point i from a centre c,
// |p_i - p_j| <= r_i + r_j, so once r_i + r_j cannot beat the best distance found, no later
// pair (sorted by decreasing r) can either.
double farthest_pair_distance(std::vector<Eigen::Vector3d> points) {
  if (points.size() < 2) return 0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& p : points) centre += p;
  centre /= static_cast<double>(points.size());
  std::vector<double> radius(points.size());
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  for (std::size_t i = 0; i < points.size(); ++i) radius[i] = (points[i] - centre).norm();
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return radius[a] > radius[b]; });

  double best_squared = 0;
  for (std::size_t a = 0; a < order.size(); ++a) {
    const std::size_t i = order[a];
    if (2 * radius[i] <= std::sqrt(best_squared)) break;
    for (std::size_t b = a + 1; b < order.size(); ++b) {
      const std::size_t j = order[b];
      if (radius[i] + radius[j] <= std::sqrt(best_squared)) break;
      best_squared = std::max(best_squared, (points[i] - points[j]).squaredNorm());
    }
  }
  return std::sqrt(best_squared);
}

}  // namespace

double exact_diameter(const std::vector<Eigen::Vector3f>& points) {
  // Below this size the hull costs more than it saves.
  constexpr std::size_t small = 64;
  std::vector<Eigen::Vector3d> candidates;
  if (points.size() > small) {
    static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "points must be packed");
    btConvexHullComputer hull;
    hull.compute(points.front().data(), sizeof(Eigen::Vector3f), static_cast<int>(points.size()), 0,
                 0);
    // The hull keeps the input index of each vertex: compare the original coordinates, not
    // Bullet's copies (btScalar may be float).
    for (int i = 0; i < hull.original_vertex_index.size(); ++i) {
      candidates.push_back(points[hull.original_vertex_index[i]].cast<double>());
    }
  }
  // Degenerate input (all points equal) yields no hull: fall back to all points.
  if (candidates.size() < 2) {
    candidates.clear();
    for (const auto& p : points) candidates.push_back(p.cast<double>());
  }
  return farthest_pair_distance(std::move(candidates));
}

}  // namespace binpick
