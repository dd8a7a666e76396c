// Volume, centre of mass and principal inertia of a closed triangle mesh of uniform density.
// Bullet's own estimate for a compound (calculatePrincipalAxisTransform) takes each hull's
// inertia from its bounding box; the mesh gives the exact answer.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "host/core/mesh.hpp"

namespace binpick {

struct MassProperties {
  double volume = 0.0;                // mm^3
  Eigen::Isometry3d principal_frame;  // part frame <- principal frame: centre + principal axes
  Eigen::Vector3d inertia_per_mass;   // principal moments / mass, mm^2
};

// Throws InputError if the mesh encloses no volume. A mesh wound inside out is accepted.
MassProperties mass_properties(const Mesh& mesh);

}  // namespace binpick
