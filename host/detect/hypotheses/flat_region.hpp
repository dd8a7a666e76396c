// The flat-region test on a hypothesis (the highest-point heuristic's blind spot): a highest
// point on a flat patch wider than any flat region of the part is not on the part (plates lying
// on a bin of shafts took most of the highest points); such a point is skipped with its reason
// and the next highest point is taken instead (docs/detect/hypotheses.md, "The flat region";
// docs/decisions/2026-12-02-flat-region.md).
//
// A flat region is what grows from a seed point over neighbouring points (within `link` of a
// point already in) that lie on the seed's tangent plane (within `tolerance`), with a normal
// within `max_angle` of the seed's, and within `radius` of the seed. Its size is a count of
// points of a cloud subsampled at the model's voxel: the model's cloud and a crop's subsample
// count alike, so the two sizes compare.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "host/core/mesh.hpp"

namespace binpick {

struct FlatRegionOptions {
  float radius = 0;       // mm, about the seed
  float tolerance = 0;    // mm, off the seed's tangent plane
  float link = 0;         // mm, to a point already in the region
  float max_angle = 20;   // degrees between a point's normal and the seed's
};

// The cloud's neighbourhoods found once (point_grid.hpp); regions grown from any seed.
class FlatRegions {
 public:
  FlatRegions(const PointCloud& cloud, const FlatRegionOptions& opt);
  // Points in the flat region grown from point `seed` (at least 1: the seed).
  std::size_t size_from(std::size_t seed) const;
  // The largest region over every seed (the part's widest flat region, for a model's cloud).
  std::size_t largest() const;

 private:
  const PointCloud& cloud_;
  FlatRegionOptions opt_;
  float cos_angle_ = 1;
  // Each point's neighbours within `link` (found once through a grid of cells `link` wide):
  // those of point i are neighbours_[first_[i] .. first_[i + 1]).
  std::vector<std::uint32_t> first_, neighbours_;
  mutable std::vector<std::uint32_t> stamp_;
  mutable std::uint32_t round_ = 0;
};

// The point of `cloud` nearest `p` (cloud not empty).
std::size_t nearest_point(const PointCloud& cloud, const Eigen::Vector3f& p);

}  // namespace binpick
