// The bin itself, one geometry for the physics and the camera: the built-in industrial bin (a
// floor, four walls with a thickness, a flat lip around the top), or a user's mesh. World frame
// (synth/physics/drop.hpp): mm, origin at the centre of the interior floor, z up; the interior
// spans x in [-w/2, w/2], y in [-d/2, d/2], z in [0, h] (--bin-size).
#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "host/core/mesh.hpp"

namespace binpick {

// The built-in bin's shape around its interior: walls and floor `wall_mm` thick, and a lip
// `rim_mm` wide (as thick as the walls) running outward around the top of the walls, its upper
// face level with the walls' tops at the interior height. Defaults: a plastic or steel
// industrial tote.
struct BuiltInBinWalls {
  double wall_mm = 10.0;
  double rim_mm = 25.0;
};

struct BinModel {
  // The built-in bin is a union of boxes, which the physics collides with exactly (Bullet's
  // boxes are its most robust static shapes); empty for a mesh bin, which collides as a static
  // triangle mesh.
  std::vector<Eigen::AlignedBox3d> boxes;
  // What the camera sees, world frame, mm, with per-vertex normals. The built-in bin's boxes
  // are closed and wound counter-clockwise from outside; a user's mesh may be open or wound
  // either way, so it is drawn from both sides (double_sided).
  Mesh mesh;
  bool double_sided = false;
  Eigen::AlignedBox3d bounds;  // of the mesh
};

// Throws InputError unless the interior is positive, the wall is in [0.5, 200] mm and the rim
// in [0, 500] mm (finite).
BinModel built_in_bin(const Eigen::Vector3d& interior_mm, const BuiltInBinWalls& walls);

// A bin from a mesh already in the world frame and in mm (e.g. load_model of --bin-mesh).
// Throws InputError for a mesh without triangles or with non-finite positions.
BinModel bin_from_mesh(Mesh mesh);

// The triangles of a box, 4 vertices a face with the face's normal, counter-clockwise seen
// from outside.
void append_box(Mesh& mesh, const Eigen::AlignedBox3d& box);

}  // namespace binpick
