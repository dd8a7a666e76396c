// A grasp in a part's model frame (mm): where a gripper takes the part and from which side
// (docs/picks.md). Grasps come from a JSON file or from the part's flat faces (train).
#pragma once

#include <cstdint>

#include <Eigen/Geometry>

namespace binpick {

struct Grasp {
  enum class Kind : std::uint32_t { suction = 0, parallel = 1 };
  Kind kind = Kind::suction;
  // Suction: the cup's centre on the surface. Parallel: midway between the finger pads.
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  // Unit: the direction the gripper moves in to reach the point (into the part).
  Eigen::Vector3d approach = Eigen::Vector3d::UnitZ();
  // Unit, across the approach: the fingers' closing axis (suction: any, kept for the frame).
  Eigen::Vector3d closing = Eigen::Vector3d::UnitX();
  double size = 0;  // suction: the cup's diameter; parallel: the opening between the pads (mm)

  // The grasp's frame in the model frame: origin the point, z the approach, x the closing axis.
  Eigen::Isometry3d frame() const {
    Eigen::Isometry3d f = Eigen::Isometry3d::Identity();
    f.linear().col(0) = closing;
    f.linear().col(1) = approach.cross(closing);
    f.linear().col(2) = approach;
    f.translation() = point;
    return f;
  }
};

// A unit vector across a (unit): the closing axis a suction grasp's frame takes, the same for the
// same a on every machine.
inline Eigen::Vector3d across(const Eigen::Vector3d& a) {
  const Eigen::Vector3d least = std::abs(a.x()) <= std::abs(a.y()) && std::abs(a.x()) <= std::abs(a.z())
                                    ? Eigen::Vector3d::UnitX()
                                : std::abs(a.y()) <= std::abs(a.z()) ? Eigen::Vector3d::UnitY()
                                                                     : Eigen::Vector3d::UnitZ();
  return (least - a * a.dot(least)).normalized();
}

}  // namespace binpick
