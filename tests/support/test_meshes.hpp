// Small closed meshes with known geometry for the decomposition and physics tests and the
// physics benchmark: one definition, so that they all measure the same parts.
#pragma once

#include <Eigen/Core>

#include "host/core/mesh.hpp"

namespace binpick::test {

// An L-profile (legs 40 and 30 mm, 5 mm thick) extruded 20 mm: a bracket-like part of
// diameter about 54 mm, like the paper's (5.2 cm); concave, closed, wound counter-clockwise
// from outside. HACD cuts it into 2 hulls.
Mesh l_bracket();

// Ring radius 20 mm, tube radius 6 mm (32 x 12 quads by default): diameter 52 mm; HACD cuts it
// into 8 hulls, one would fill the hole. More quads make a dense mesh of the same shape.
Mesh torus(int around = 32, int across = 12);

// An axis-aligned box from the origin to `size`, outward-facing triangles.
Mesh box(const Eigen::Vector3f& size);

}  // namespace binpick::test
