// A gripper as a few solids in a grasp's frame (grasp.hpp: origin the grasp point, z the approach
// into the part, x the closing axis): what must stay clear of everything but the grasped part.
// A suction tool is its cup (a short cylinder of the cup's diameter, the stand-off) and the tool's
// body above it; a parallel gripper two fingers at the grasp's opening and the palm joining them.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

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
// Points on the solid's surface that stand for it against planes (a bin's walls and floor): a
// box's corners and face centres, a cylinder's two rims at 16 points each and its end centres.
std::vector<Eigen::Vector3d> surface_samples(const GripperSolid& solid);

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

// What of a bin the solids at grasp_in_frame hit, in the frame of a bin whose interior floor
// centre is `origin` with axes `axes` (columns x, y, z up) and interior W, D, H: "the bin's wall"
// (a sample point below the rim outside the interior), "the bin's floor" (below it), or "".
// Within tolerance (mm) of the interior is inside.
std::string bin_contact(const std::vector<GripperSolid>& solids,
                        const Eigen::Isometry3d& grasp_in_frame, const Eigen::Matrix3d& axes,
                        const Eigen::Vector3d& origin, const Eigen::Vector3d& interior,
                        double tolerance);

// The suction tool a part of this diameter gets without --gripper: the cup given (the grasps'),
// a stand-off of 10 % of the diameter, a body as wide as the cup and two diameters long.
Gripper default_suction_gripper(double part_diameter, double cup_diameter);

}  // namespace binpick
