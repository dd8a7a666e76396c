// Suction grasps from a part's flat faces (docs/picks.md): where a cup of the given
// diameter lies on the surface all round within a flatness tolerance, with nothing of the part
// above the face within the cup's width, the grasps nearest the part's centre, spread out.
#pragma once

#include <vector>

#include "host/core/grasp.hpp"
#include "host/core/mesh.hpp"

namespace binpick {

struct SuctionGraspOptions {
  double cup_diameter = 0;  // mm, > 0
  double flatness = 0;      // mm, > 0: the surface under the cup within this of its plane
  double spacing = 0;       // mm, > 0: the points' spacing (a point this near stands for the surface)
  double apart = 0;          // mm: grasps on one face at least this far apart (0: the cup's radius)
  std::size_t max_grasps = 48;
};

// Of surface points with unit outward normals (the model's refinement points: even, dense),
// the grasps whose cup the surface holds (at 8 points round the cup's rim and 4 halfway in, a
// point within `spacing` across and `flatness` of the tangent plane, facing within 45 degrees the
// same way: a cup's lip follows a gently curved face) with no point higher than `flatness` above the plane within the cup's
// radius; nearest the points' centroid first, no two closer than `apart` on one face (normals
// within 10 degrees). Deterministic; empty when no face holds the cup.
std::vector<Grasp> find_suction_grasps(const PointCloud& surface, const SuctionGraspOptions& options);

}  // namespace binpick
