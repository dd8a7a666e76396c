// A gripper as a few solids in a grasp's frame (grasp.hpp: origin the grasp point, z the approach
// into the part, x the closing axis): what must stay clear of everything but the grasped part.
// A suction tool is its cup (a short cylinder of the cup's diameter, the stand-off) and the tool's
// body above it; a parallel gripper two fingers at the grasp's opening and the palm joining them.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "host/core/grasp.hpp"

namespace binpick {

// An axis-aligned box (half extents) or a cylinder along z (radius half.x(), half length half.z())
// about centre, in the grasp's frame (mm).
struct GripperSolid {
  enum class Shape : std::uint32_t { box = 0, cylinder = 1 };
  Shape shape = Shape::box;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
};

// Signed distance (mm) from p to the solid: negative inside.
double signed_distance(const GripperSolid& solid, const Eigen::Vector3d& p);

struct Gripper {
  Grasp::Kind kind = Grasp::Kind::suction;
  // Suction: cup diameter, stand-off (the cup's length), body diameter and length (mm).
  // Parallel: finger width (along the closing axis), depth (across it) and length (along the
  // approach), and palm height above the fingers (mm).
  double a = 0, b = 0, c = 0, d = 0;

  static Gripper suction(double cup_diameter, double standoff, double body_diameter,
                         double body_length);
  static Gripper parallel(double finger_width, double finger_depth, double finger_length,
                          double palm_height);

  // The solids at a grasp of this gripper's kind (a parallel gripper's fingers at its opening).
  std::vector<GripperSolid> solids(const Grasp& grasp) const;
  // Reach beyond the grasp point along -z (mm): how far up the approach the solids go.
  double length() const;
  std::string describe() const;
};

// The suction tool a part of this diameter gets without --gripper: cup 20 % of the diameter
// (train's default cup), stand-off 10 %, a body as wide as the cup and two diameters long.
Gripper default_suction_gripper(double part_diameter, double cup_diameter);

}  // namespace binpick
