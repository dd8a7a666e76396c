// A convex hull as the intersection of half-spaces: inside tests and distances for merging
// hulls (hull_merge.hpp) and checking that they cover the mesh (hull_cover.hpp).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "synth/decompose/convex_parts.hpp"

namespace binpick {

struct HalfSpaces {
  std::vector<Eigen::Vector4d> planes;    // n.p + d <= 0 inside, |n| = 1
  Eigen::Vector3d lo, hi;                 // bounding box, for quick rejection
  std::vector<Eigen::Vector3f> vertices;  // the hull's extreme points only
};

// The convex hull of `points` (Bullet's btConvexHullComputer).
HalfSpaces half_spaces(const std::vector<Eigen::Vector3f>& points);

// One per hull, in order.
std::vector<HalfSpaces> half_spaces_of(const ConvexParts& parts);

bool contains(const HalfSpaces& hull, const Eigen::Vector3d& p);

// Largest signed plane distance: how far p lies outside (> 0; exact near faces, a lower bound
// near edges and corners), or minus its depth inside.
double outside_distance(const HalfSpaces& hull, const Eigen::Vector3d& p);

}  // namespace binpick
