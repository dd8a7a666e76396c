// Assembles a closed part surface patch by patch. Each patch adds its own vertices with the
// patch's true normals (so normals are never averaged across a sharp edge); patches meet
// exactly because they take the shared boundary points from the same computation. Triangles are
// oriented from the normals they are given, so shape code need not track winding.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "host/core/mesh.hpp"

namespace binpick {

class PartBuilder {
 public:
  std::uint32_t vertex(const Eigen::Vector3d& position, const Eigen::Vector3d& normal);

  // Triangle a b c, reversed if needed so its geometric normal points along the sum of its
  // vertex normals (the outside).
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c);

  // A convex quad a b c d (in order around it), as two triangles.
  void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d);

  // A planar convex polygon given by its boundary in order (collinear points allowed), with
  // outward normal; fanned from its centroid so collinear points stay proper vertices.
  void convex_polygon(const std::vector<Eigen::Vector3d>& boundary, const Eigen::Vector3d& normal);

  // The mesh in float, with vertices that share position and normal merged.
  Mesh build() const;

 private:
  std::vector<Eigen::Vector3d> positions_;
  std::vector<Eigen::Vector3d> normals_;
  std::vector<std::array<std::uint32_t, 3>> triangles_;
};

// Exact unit vector at angle 2 pi i / n: quarter turns give exact 0 and +-1, so points meant
// to coincide (seams on an axis plane) do.
Eigen::Vector2d unit_circle_point(int i, int n);

// Point at sample i of n around the z axis, at this radius and height.
Eigen::Vector3d ring_point(int i, int n, double radius, double z);

// The band swept by the profile segment from (radius r0, height z0) to (r1, z1) about the z
// axis, in n quads, with the segment's true normal turned to each sample. The outside is on the
// right of the segment walked from (r0, z0) to (r1, z1) with r to the right and z up, so a
// profile walked from the bottom up gives outward bands (a flat ring if z0 == z1; use
// convex_polygon for a disc, whose centre would be a degenerate quad here).
void add_surface_of_revolution(PartBuilder& b, int n, double r0, double z0, double r1, double z1);

}  // namespace binpick
