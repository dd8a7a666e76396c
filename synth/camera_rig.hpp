// Where the sensor is and what it is: by default above the centre of the bin floor, looking
// straight down (paper IV), with camera_for_bin's intrinsics; optionally other intrinsics and a
// tilt. World frame (synth/physics/drop.hpp): origin at the centre of the bin floor, z up.
// Camera frame (OpenCV/BOP): z along the view, y down the image; untilted, x_c = x_w,
// y_c = -y_w, z_c = -z_w, so the image shows the bin as seen from above with +x to the right.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <optional>

#include "synth/render/bin_camera.hpp"

namespace binpick {

struct CameraRig {
  // Distance from the centre of the bin floor to the camera, along the optical axis.
  double height_mm = 1000.0;
  // The camera turned about the world x axis through the centre of the bin floor, which stays
  // on the optical axis at height_mm: positive tilts move the camera towards -y (the image's
  // bottom edge), so it looks into the bin towards the +y wall, seen at the top of the image.
  double tilt_deg = 0.0;
  // Then turned about its own optical axis: the bin shows turned by this much in the image,
  // counter-clockwise as the image is seen (its x axis, drawn to the right untilted, rises).
  double roll_deg = 0.0;
  std::uint32_t width = 1600, height = 900;
  std::optional<std::array<double, 4>> intrinsics;  // fx, fy, cx, cy; none: camera_for_bin's
};

struct SceneView {
  RenderCamera camera;
  Eigen::Isometry3d world_to_camera;
};

// The rig's world -> camera transform.
Eigen::Isometry3d world_to_camera(double camera_height_mm, double tilt_deg = 0.0,
                                  double roll_deg = 0.0);

// Throws InputError for a tilt that is not finite or beyond 80 degrees either way, a roll not
// finite or beyond 180 degrees either way, intrinsics
// that are not finite or focal lengths that are not positive.
void validate_camera_rig(const CameraRig& rig);

// The camera for a bin of this interior whose geometry spans `bin_bounds` (world, mm): the
// rig's intrinsics (default: camera_for_bin's for the untilted camera), and clipping planes
// that enclose the bin from any tilt: near = half the distance to the bin's nearest bounding
// box corner (at least 2 % of height_mm), far = 5 % beyond its farthest.
SceneView scene_view(const CameraRig& rig, const Eigen::Vector3d& interior_mm,
                     const Eigen::AlignedBox3d& bin_bounds);

}  // namespace binpick
