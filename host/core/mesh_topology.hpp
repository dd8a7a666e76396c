// Vertex welding, clean-up and the closedness check of triangle meshes.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "host/core/mesh.hpp"

namespace binpick {

// For each point, the index of the first point with exactly the same coordinates (+0 == -0).
std::vector<std::uint32_t> first_index_at_same_position(const std::vector<Eigen::Vector3f>& points);

// Merges vertices that have the same position and (if the mesh has normals) the same normal,
// so a triangle soup (STL) becomes an indexed mesh while sharp edges stay sharp.
void merge_duplicate_vertices(Mesh& mesh);

// Drops triangles that use one vertex twice (they have no area and no orientation).
void remove_collapsed_triangles(Mesh& mesh);

// Drops vertices that no triangle uses, renumbering the triangles.
void remove_unreferenced_vertices(Mesh& mesh);

// Edge statistics of a mesh after welding vertices by position (so vertices duplicated to keep
// sharp normals do not count as boundaries). A closed, consistently oriented mesh has every
// undirected edge used exactly once in each direction.
struct TopologyReport {
  std::size_t boundary_edges = 0;        // used by one triangle only
  std::size_t misoriented_edges = 0;     // used twice in the same direction
  std::size_t non_manifold_edges = 0;    // used by more than two triangles
  std::size_t degenerate_triangles = 0;  // two corners at one position, or zero area
  bool closed_and_oriented() const {
    return boundary_edges == 0 && misoriented_edges == 0 && non_manifold_edges == 0 &&
           degenerate_triangles == 0;
  }
};
TopologyReport check_topology(const Mesh& mesh);

}  // namespace binpick
