// Per-pixel normals of an organised point image: a least-squares plane over a window,
// oriented towards the camera (kernels/scene_normals.cl).
#pragma once

#include <cstdint>
#include <vector>

#include "host/runtime/cl/cl_buffer.hpp"
#include "host/detect/scene/depth_to_points.hpp"

namespace binpick {

struct NormalOptions {
  int radius = 2;  // window of (2r+1)^2 pixels; r in [0, 32]
  // Neighbours farther than this (mm) from the centre point are ignored, so normals do not
  // bleed across depth discontinuities; about 20 % of the part diameter suits the paper's scene.
  float max_distance = 10.0f;
  // > 0: a metric neighbourhood instead of `radius`: the points within this many mm (and within
  // max_distance), found in a window that covers it at the point's depth (bp_metric_window in
  // kernels/scene_shared.h; focal = the camera's focal length in pixels). A fixed pixel window
  // shrinks in mm with distance and, a few pixels wide, turns sensor noise into normal noise.
  float metric_radius = 0.0f;
  float focal = 0.0f;
};

// Throws InputError unless points holds 4 floats per pixel of its width x height.
void check_point_image(const PointImage& points);
void check(const NormalOptions& opt);

// Routine: the normals_from_points kernel on the shared device. Out: per pixel (nx, ny, nz, 1)
// with n . p < 0, or all 0 (no data, fewer than 3 neighbours, or a degenerate fit).
PointImage normals_from_points(ocl::Device& dev, const PointImage& points,
                               const NormalOptions& opt = {});
// Reference: the same covariance in double, solved by Eigen's SelfAdjointEigenSolver.
PointImage normals_from_points_reference(const PointImage& points, const NormalOptions& opt = {});

// The kernel on device buffers (float4 a pixel), enqueued without waiting.
void enqueue_normals_from_points(ocl::Device& dev, const ocl::Buffer<float>& points,
                                 std::uint32_t width, std::uint32_t height,
                                 const NormalOptions& opt, ocl::Buffer<float>& normals);

// Normals of listed pixels only (row-major indices into the image), on a point image already on
// the device: out[j] (nx, ny, nz, 1 or all 0) is the normal of pixel pixels[j], the same value
// the full-image kernel gives there. The detector needs normals only at the few thousand points
// it keeps of a hypothesis' neighbourhood, not at 1.4 M pixels. Throws InputError for a pixel
// outside the image or bad options.
std::vector<float> normals_at_pixels(ocl::Device& dev, const ocl::Buffer<float>& points,
                                     std::uint32_t width, std::uint32_t height,
                                     const std::vector<std::uint32_t>& pixels,
                                     const NormalOptions& opt = {});
// The same on a host image (uploads it).
std::vector<float> normals_at_pixels(ocl::Device& dev, const PointImage& points,
                                     const std::vector<std::uint32_t>& pixels,
                                     const NormalOptions& opt = {});
// Reference: normals_from_points_reference's value at each listed pixel.
std::vector<float> normals_at_pixels_reference(const PointImage& points,
                                               const std::vector<std::uint32_t>& pixels,
                                               const NormalOptions& opt = {});

}  // namespace binpick
