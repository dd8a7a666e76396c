// Simple measures and in-place edits of a Mesh's geometry.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "host/core/mesh.hpp"

namespace binpick {

struct BoundingBox {
  Eigen::Vector3f min;
  Eigen::Vector3f max;
  Eigen::Vector3f size() const { return max - min; }
  Eigen::Vector3f center() const { return (min + max) / 2; }
};

// Axis-aligned box of the points; all zeros for no points.
BoundingBox bounding_box(const std::vector<Eigen::Vector3f>& points);

// Volume enclosed by the triangles (divergence theorem, in double): positive for a closed mesh
// whose triangles are counter-clockwise seen from outside.
double signed_volume(const Mesh& mesh);

// Scales positions about the origin; normals are unchanged (factor must be positive).
void scale_mesh(Mesh& mesh, double factor);

void translate_mesh(Mesh& mesh, const Eigen::Vector3f& offset);

}  // namespace binpick
