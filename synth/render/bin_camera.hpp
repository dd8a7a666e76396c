// The sensor of a synthetic bin: an OpenCV/BOP pinhole camera looking straight down into the
// bin, with the clipping planes the z-buffer needs (paper, equation 1).
#pragma once

#include <cstdint>

#include <Eigen/Core>

#include "synth/render/zbuffer_to_points.hpp"

namespace binpick {

// Pixel (u, v) has its centre at integer (u, v); a camera-frame point (x, y, z), z along the
// optical axis, x right, y down, projects to u = fx x / z + cx, v = fy y / z + cy.
struct RenderCamera {
  std::uint32_t width = 1600, height = 900;
  double fx = 0, fy = 0, cx = 0, cy = 0;
  double near_mm = 0, far_mm = 0;  // clipping planes: surfaces outside [near, far] are not seen
};

// The camera camera_height_mm above the bin floor, on the bin's axis, looking down: square
// pixels, principal point at the image centre ((w - 1) / 2, (h - 1) / 2), and the focal length
// that shows the top rim of the bin interior (nearest the camera, so widest in the image) with
// a 2 % margin. near = half the distance to the rim, far = 5 % beyond the floor.
// Throws InputError unless all sizes are positive and the camera is above the rim.
RenderCamera camera_for_bin(double bin_x_mm = 600, double bin_y_mm = 400, double bin_z_mm = 300,
                            double camera_height_mm = 1000, std::uint32_t width = 1600,
                            std::uint32_t height = 900);

// The camera whose pixel (u, v) samples the point (u + 0.5, v + 0.5) of `camera`: the principal
// point moved by -0.5 px. The BOP toolkit's renderers (renderer_vispy.py's _calc_calib_proj,
// bop_renderer's calculateProjectionMatrix) put pixel (i, j) there, half a pixel off the
// convention above, which binpick's depth images follow. The annotations the toolkit renders
// (calc_gt_info.py's scene_gt_info.json, calc_masks.py's masks, VSD's model depths) are
// reproduced by drawing the models with this camera; distances along the rays are still
// computed with the image's own intrinsics, as the toolkit does.
RenderCamera bop_toolkit_sampling(const RenderCamera& camera);

// Throws InputError unless the camera can render (positive size and focal lengths, 0 < near < far).
void check_camera(const RenderCamera& camera);

// Pixel coordinates of a camera-frame point (z > 0).
Eigen::Vector2d project(const RenderCamera& camera, const Eigen::Vector3d& p);

// The z-buffer value b in [0, 1] of depth z (near -> 0, far -> 1), the inverse of equation 1.
double zbuffer_value(const RenderCamera& camera, double z_mm);

ZBufferCamera zbuffer_camera(const RenderCamera& camera);

}  // namespace binpick
