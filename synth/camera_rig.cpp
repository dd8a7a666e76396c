#include "synth/camera_rig.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "host/core/error.hpp"

namespace binpick {

Eigen::Isometry3d world_to_camera(double camera_height_mm, double tilt_deg, double roll_deg) {
  Eigen::Isometry3d straight_down = Eigen::Isometry3d::Identity();
  straight_down.linear() = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  straight_down.translation() = Eigen::Vector3d(0.0, 0.0, camera_height_mm);
  // The camera turned by the tilt about world x through the origin: camera -> world gains the
  // rotation on the left, so world -> camera gains its inverse on the right.
  const double tilt = tilt_deg * std::numbers::pi / 180.0;
  const Eigen::Isometry3d tilted =
      tilt_deg == 0.0 ? straight_down
                      : straight_down * Eigen::AngleAxisd(-tilt, Eigen::Vector3d::UnitX());
  if (roll_deg == 0.0) return tilted;
  // Then about its own z (the optical axis, the origin stays on it): the camera frame's
  // coordinates turn the other way. Image y points down, so a world x seen at (1, 0) goes to
  // (cos, -sin): up the image, counter-clockwise as seen.
  const double roll = roll_deg * std::numbers::pi / 180.0;
  return Eigen::Isometry3d(Eigen::AngleAxisd(-roll, Eigen::Vector3d::UnitZ())) * tilted;
}

void validate_camera_rig(const CameraRig& rig) {
  if (!(std::isfinite(rig.tilt_deg) && std::abs(rig.tilt_deg) <= 80.0))
    throw InputError(
        fmt::format("--camera-tilt must be between -80 and 80 degrees, got {}", rig.tilt_deg));
  if (!(std::isfinite(rig.roll_deg) && std::abs(rig.roll_deg) <= 180.0))
    throw InputError(
        fmt::format("--camera-roll must be between -180 and 180 degrees, got {}", rig.roll_deg));
  if (rig.intrinsics) {
    const auto& k = *rig.intrinsics;
    if (!(std::isfinite(k[0]) && std::isfinite(k[1]) && std::isfinite(k[2]) &&
          std::isfinite(k[3]) && k[0] > 0 && k[1] > 0))
      throw InputError(
          fmt::format("--intrinsics needs fx,fy,cx,cy in pixels, finite, with fx and fy positive; "
                      "got {},{},{},{}",
                      k[0], k[1], k[2], k[3]));
  }
}

SceneView scene_view(const CameraRig& rig, const Eigen::Vector3d& interior,
                     const Eigen::AlignedBox3d& bin_bounds) {
  validate_camera_rig(rig);
  SceneView view;
  view.camera = camera_for_bin(interior.x(), interior.y(), interior.z(), rig.height_mm, rig.width,
                               rig.height);
  if (rig.intrinsics) {
    const auto& k = *rig.intrinsics;
    view.camera.fx = k[0];
    view.camera.fy = k[1];
    view.camera.cx = k[2];
    view.camera.cy = k[3];
  }
  view.world_to_camera = world_to_camera(rig.height_mm, rig.tilt_deg, rig.roll_deg);
  // The bin and its interior filled to the brim; parts above it are covered by the margin.
  Eigen::AlignedBox3d box = bin_bounds;
  box.extend(Eigen::Vector3d(-interior.x() / 2, -interior.y() / 2, 0.0));
  box.extend(Eigen::Vector3d(interior.x() / 2, interior.y() / 2, interior.z()));
  double nearest = INFINITY, farthest = 0.0;
  for (int c = 0; c < 8; ++c) {
    const double z = (view.world_to_camera * box.corner(Eigen::AlignedBox3d::CornerType(c))).z();
    nearest = std::min(nearest, z);
    farthest = std::max(farthest, z);
  }
  if (!(farthest > 0))
    throw InputError("the camera looks away from the bin: lower the tilt or raise the camera");
  view.camera.near_mm = std::max(0.5 * nearest, 0.02 * rig.height_mm);
  view.camera.far_mm = 1.05 * farthest;
  check_camera(view.camera);
  return view;
}

}  // namespace binpick
