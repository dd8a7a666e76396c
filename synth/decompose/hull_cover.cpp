#include "synth/decompose/hull_cover.hpp"

#include <algorithm>
#include <limits>
#include <vector>

#include "synth/decompose/half_spaces.hpp"

namespace binpick {
namespace {

// The hull `p` lies least outside of, and by how much.
std::pair<std::size_t, double> nearest_hull(const std::vector<HalfSpaces>& hulls,
                                            const Eigen::Vector3d& p) {
  std::size_t best = 0;
  double least = std::numeric_limits<double>::infinity();
  for (std::size_t h = 0; h < hulls.size(); ++h) {
    const double out = outside_distance(hulls[h], p);
    if (out < least) {
      least = out;
      best = h;
    }
  }
  return {best, least};
}

}  // namespace

double farthest_outside_mm(const ConvexParts& parts, const Mesh& mesh) {
  const std::vector<HalfSpaces> hulls = half_spaces_of(parts);
  double worst = 0.0;
  if (hulls.empty()) return mesh.positions.empty() ? 0.0 : std::numeric_limits<double>::infinity();
  for (const auto& p : mesh.positions)
    worst = std::max(worst, nearest_hull(hulls, p.cast<double>()).second);
  return worst;
}

ConvexParts cover_mesh(const ConvexParts& parts, const Mesh& mesh, double tolerance_mm) {
  if (parts.hulls.empty()) return parts;
  std::vector<HalfSpaces> hulls = half_spaces_of(parts);
  // Hulls only grow, so a vertex once covered stays covered: each round looks only at the
  // vertices still outside. A grown hull covers more of them than the one it was grown for, so
  // the rounds repeat until none is left; each adds at least one vertex, so they end.
  std::vector<Eigen::Vector3d> outside;
  for (const auto& p : mesh.positions) outside.push_back(p.cast<double>());
  for (;;) {
    std::vector<std::pair<double, Eigen::Vector3d>> farthest(
        hulls.size(), {0.0, Eigen::Vector3d::Zero()});
    std::vector<Eigen::Vector3d> still;
    for (const auto& p : outside) {
      const auto [h, out] = nearest_hull(hulls, p);
      if (out <= tolerance_mm) continue;
      still.push_back(p);
      // Only the farthest outlier of each hull is added per round: it covers its neighbours,
      // and adding them all would give the hull every vertex of a curved surface.
      if (out > farthest[h].first) farthest[h] = {out, p};
    }
    if (still.empty()) break;
    for (std::size_t h = 0; h < hulls.size(); ++h) {
      if (farthest[h].first <= 0.0) continue;
      std::vector<Eigen::Vector3f> points = hulls[h].vertices;
      points.push_back(farthest[h].second.cast<float>());
      hulls[h] = half_spaces(points);
    }
    outside = std::move(still);
  }
  ConvexParts covered;
  for (auto& h : hulls) covered.hulls.push_back(ConvexHull{std::move(h.vertices)});
  return covered;
}

}  // namespace binpick
