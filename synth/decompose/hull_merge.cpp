#include "synth/decompose/hull_merge.hpp"

#include "synth/decompose/half_spaces.hpp"

#include <Eigen/Geometry>
#include <limits>
#include <vector>

namespace binpick {
namespace {

// Samples per axis of a hull's bounding box: 20^3 = 8000 points resolve 0.1 % of a hull's
// volume, and a decomposition takes well under a second.
constexpr int kGrid = 20;

// The volume (mm^3) of the part of `region` that none of `covered` contains.
double uncovered_volume(const HalfSpaces& region, const std::vector<HalfSpaces>& covered) {
  const Eigen::Vector3d size = region.hi - region.lo;
  const double cell = size.prod() / (kGrid * kGrid * kGrid);
  double uncovered = 0.0;
  for (int a = 0; a < kGrid; ++a)
    for (int b = 0; b < kGrid; ++b)
      for (int c = 0; c < kGrid; ++c) {
        const Eigen::Vector3d p =
            region.lo + Eigen::Vector3d(a + 0.5, b + 0.5, c + 0.5).cwiseProduct(size) / kGrid;
        if (!contains(region, p)) continue;
        bool inside = false;
        for (const auto& h : covered)
          if ((inside = contains(h, p))) break;
        if (!inside) uncovered += cell;
      }
  return uncovered;
}

bool boxes_touch(const HalfSpaces& a, const HalfSpaces& b) {
  return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all();
}

}  // namespace

double union_volume(const ConvexParts& parts) {
  // Each point counts for the first hull that contains it, so overlaps count once.
  const std::vector<HalfSpaces> hulls = half_spaces_of(parts);
  double volume = 0.0;
  for (std::size_t i = 0; i < hulls.size(); ++i)
    volume += uncovered_volume(hulls[i], std::vector<HalfSpaces>(hulls.begin(), hulls.begin() + i));
  return volume;
}

ConvexParts merge_hulls(const ConvexParts& parts, const HullMergeOptions& options) {
  std::vector<HalfSpaces> hulls = half_spaces_of(parts);
  const double volume = union_volume(parts);
  double added_total = 0.0;
  while (hulls.size() > 1) {
    double least = std::numeric_limits<double>::infinity();
    std::size_t best_i = 0, best_j = 0;
    HalfSpaces best;
    for (std::size_t i = 0; i < hulls.size(); ++i)
      for (std::size_t j = i + 1; j < hulls.size(); ++j) {
        if (!boxes_touch(hulls[i], hulls[j])) continue;  // far apart: the gap would be filled
        std::vector<Eigen::Vector3f> both = hulls[i].vertices;
        both.insert(both.end(), hulls[j].vertices.begin(), hulls[j].vertices.end());
        HalfSpaces merged = half_spaces(both);
        const double added = uncovered_volume(merged, hulls);
        if (added < least) {
          least = added;
          best_i = i;
          best_j = j;
          best = std::move(merged);
        }
      }
    if (!(least <= options.max_added_per_merge * volume) ||
        added_total + least > options.max_added_total * volume)
      break;
    added_total += least;
    hulls[best_i] = std::move(best);
    hulls.erase(hulls.begin() + static_cast<std::ptrdiff_t>(best_j));
  }
  ConvexParts merged;
  for (auto& h : hulls) merged.hulls.push_back(ConvexHull{std::move(h.vertices)});
  return merged;
}

}  // namespace binpick
