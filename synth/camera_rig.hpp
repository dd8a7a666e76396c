// Where the sensor is: above the centre of the bin floor, looking straight down (paper IV).
// World frame (synth/physics/drop.hpp): origin at the centre of the bin floor, z up.
// Camera frame (OpenCV/BOP): z along the view, y down the image; here x_c = x_w, y_c = -y_w,
// z_c = -z_w, so the image shows the bin as seen from above with +x to the right.
#pragma once

#include <Eigen/Geometry>

namespace binpick {

inline Eigen::Isometry3d world_to_camera(double camera_height_mm) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  T.translation() = Eigen::Vector3d(0.0, 0.0, camera_height_mm);
  return T;
}

}  // namespace binpick
