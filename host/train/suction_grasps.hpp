// Suction grasps from a part's flat faces (docs/picks.md): where a cup of the given
// diameter lies on the surface all round within a flatness tolerance, with nothing of the part
// above the face within the cup's width, the grasps nearest the part's centre, spread out.
#pragma once

#include <vector>

#include "host/core/grasp.hpp"
#include "host/core/mesh.hpp"
#include "host/core/point_grid.hpp"

namespace binpick {

struct SuctionGraspOptions {
  double cup_diameter = 0;  // mm, > 0
  double flatness = 0;      // mm, > 0: the surface under the cup within this of its plane
  double spacing = 0;       // mm, > 0: the points' spacing (a point this near stands for the surface)
  double apart = 0;          // mm: grasps on one face at least this far apart (0: the cup's radius)
  std::size_t max_grasps = 48;
};

// The options train uses for a part of this diameter and voxel (mm): the cup given (0: 10 % of
// the diameter), flatness 15 % of the cup, the lip's reach 0.75 refinement voxels.
SuctionGraspOptions suction_grasp_options(double diameter, double voxel_size, double cup_diameter);

// The radius a grid for cup_held needs (and its queries read): the cup's, the lip's reach and
// the flatness.
inline float cup_reach(const SuctionGraspOptions& o) {
  return float(o.cup_diameter / 2 + o.spacing + o.flatness);
}

// Whether the surface (unit normals; index a PointGrid over it of cell cup_reach(o)) holds a cup
// whose lip lies in the plane through p with normal n (out of the part, towards the cup): at 8
// points round the rim and 4 halfway in a point within `spacing` across and `flatness` of the
// plane, facing within 45 degrees the same way, and no point higher than `flatness` above the
// plane within the cup's radius.
bool cup_held(const PointGrid& index, const PointCloud& surface, const Eigen::Vector3d& p,
              const Eigen::Vector3d& n, const SuctionGraspOptions& o);

// Of surface points with unit outward normals (the model's refinement points: even, dense),
// the grasps whose cup the surface holds (cup_held); those that may slip furthest along their
// face and still seal first (the distance to where the cup is not held, in lip spacings up to
// the cup's radius), then nearest the points' centroid; no two closer than `apart` on one face
// (normals within 10 degrees). Deterministic; empty when no face holds the cup.
std::vector<Grasp> find_suction_grasps(const PointCloud& surface, const SuctionGraspOptions& options);

}  // namespace binpick
