// The flat-region test on a hypothesis (the highest-point heuristic's blind spot): a highest
// point on a flat patch wider than any flat region of the part is not on the part (a plate lying
// on the parts sought); such a point is skipped with its reason
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
#include <map>
#include <string>
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

// The skip rule for one model (`--flat-region`): a crop's subsample about a highest point is
// skipped when the flat region the point lies on holds more than `ratio` times the points of the
// part's widest. Regions within half the diameter, a plane tolerance of half a voxel or twice
// the depth noise in steps of a quarter voxel; the part's widest is found once per step. Off for
// ratio 0 and for thin parts (sheets stacked flat join their neighbours' faces, and a sheet's face
// is its widest region: docs/decisions/2026-12-02-flat-region-thin-parts.md).
class FlatRegionSkip {
 public:
  FlatRegionSkip(const PointCloud& model, float diameter, float voxel_size, double ratio,
                 bool thin);
  // Why to skip the hypothesis at `point` (its reason), or "" to keep it. noise: the image's
  // depth noise (mm); voxel_factor: the scene voxels' stretch along the camera's axis.
  std::string reason(const PointCloud& sample, const Eigen::Vector3f& point, double noise,
                     double voxel_factor) const;

 private:
  const PointCloud& model_;
  float diameter_ = 0, voxel_size_ = 0;
  double ratio_ = 0;
  bool thin_ = false;
  mutable std::map<int, std::size_t> widest_;  // the part's widest region, by tolerance step
};

}  // namespace binpick
