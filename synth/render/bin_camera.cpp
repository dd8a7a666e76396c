#include "synth/render/bin_camera.hpp"

#include <algorithm>
#include <string>

#include "host/core/error.hpp"

namespace binpick {

RenderCamera camera_for_bin(double bin_x_mm, double bin_y_mm, double bin_z_mm,
                            double camera_height_mm, std::uint32_t width, std::uint32_t height) {
  if (!(bin_x_mm > 0 && bin_y_mm > 0 && bin_z_mm > 0 && width > 0 && height > 0))
    throw InputError("camera_for_bin: the bin and the image need positive sizes");
  const double rim_distance = camera_height_mm - bin_z_mm;
  if (!(rim_distance > 0))
    throw InputError("camera_for_bin: the camera (" + std::to_string(camera_height_mm) +
                     " mm) must be above the bin's rim (" + std::to_string(bin_z_mm) + " mm)");
  constexpr double kMargin = 0.98;  // the rim fills at most 98 % of the half-image
  RenderCamera cam;
  cam.width = width;
  cam.height = height;
  cam.cx = (width - 1) / 2.0;
  cam.cy = (height - 1) / 2.0;
  // The rim's corner at (bin_x / 2, bin_y / 2, rim_distance) must land within the margin.
  const double f_x = kMargin * (width / 2.0) * rim_distance / (bin_x_mm / 2);
  const double f_y = kMargin * (height / 2.0) * rim_distance / (bin_y_mm / 2);
  cam.fx = cam.fy = std::min(f_x, f_y);
  cam.near_mm = 0.5 * rim_distance;
  cam.far_mm = 1.05 * camera_height_mm;
  return cam;
}

RenderCamera bop_toolkit_sampling(const RenderCamera& camera) {
  RenderCamera shifted = camera;
  shifted.cx -= 0.5;
  shifted.cy -= 0.5;
  return shifted;
}

void check_camera(const RenderCamera& c) {
  if (c.width == 0 || c.height == 0 || c.width > 16384 || c.height > 16384)
    throw InputError("render camera: image size " + std::to_string(c.width) + " x " +
                     std::to_string(c.height) + " is not in 1..16384");
  if (!(c.fx > 0 && c.fy > 0 && c.near_mm > 0 && c.far_mm > c.near_mm))
    throw InputError("render camera needs positive focal lengths and 0 < near < far");
}

Eigen::Vector2d project(const RenderCamera& c, const Eigen::Vector3d& p) {
  return {c.fx * p.x() / p.z() + c.cx, c.fy * p.y() / p.z() + c.cy};
}

double zbuffer_value(const RenderCamera& c, double z) {
  return c.far_mm * (z - c.near_mm) / (z * (c.far_mm - c.near_mm));
}

ZBufferCamera zbuffer_camera(const RenderCamera& c) {
  return {c.width, c.height, float(c.fx), float(c.fy), float(c.cx), float(c.cy),
          float(c.near_mm), float(c.far_mm)};
}

}  // namespace binpick
