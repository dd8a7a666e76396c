// The neighbourhood of a hypothesis: the scene points (with normals) inside a sphere, in pixel
// order (kernels/scene_crop.cl; a deterministic prefix-sum compaction).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "host/runtime/cl/cl_buffer.hpp"
#include "host/detect/scene/scene_prepare.hpp"
#include "host/core/mesh.hpp"
#include "host/detect/scene/depth_to_points.hpp"

namespace binpick {

struct CropOptions {
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();  // mm, camera frame
  float radius = 60.0f;                               // mm; points at exactly radius are kept
  bool require_normals = true;  // drop points without a valid normal (useless to PPF voting)
};

// Routine: points (and normals: same size, float4 a pixel) inside the sphere, pixel order.
PointCloud crop_sphere(ocl::Device& dev, const PointImage& points, const PointImage& normals,
                       const CropOptions& opt);
// Reference: the same predicate in plain C++; equal to the routine point for point.
PointCloud crop_sphere_reference(const PointImage& points, const PointImage& normals,
                                 const CropOptions& opt);

// On device buffers of n pixels (one small read of the chunk counts, then the crop).
PointCloud crop_sphere(ocl::Device& dev, const ocl::Buffer<float>& points,
                       const ocl::Buffer<float>& normals, std::size_t n, const CropOptions& opt);

// On a prepared scene: the kernels on its device buffers if it has them, else the C++ reference
// on its host images (a scene from prepare_scene_reference).
PointCloud crop_sphere(const PreparedScene& scene, const CropOptions& opt);

// The pixels of a sphere's neighbourhood before normals are known: every pixel with data whose
// point lies inside the sphere (require_normals is ignored), in pixel order.
struct CroppedPixels {
  std::vector<std::uint32_t> pixels;     // row-major pixel index of each point
  std::vector<Eigen::Vector3f> points;   // its point (mm)
};

// A pixel rectangle {x0, y0, x1, y1} (half-open) that holds every pixel whose point (as
// depth_to_points computes it for this camera) can lie inside the sphere: its projection, with
// a margin far above float rounding. The whole image when the sphere reaches the camera plane.
std::array<std::uint32_t, 4> crop_pixel_rect(const bp_camera& cam, const CropOptions& opt);

// Routine: scans only crop_pixel_rect (kernels crop_rect_count/scatter); points float4 a pixel
// of a cam.width x cam.height image on the device. With a "may be used" mask (one byte a pixel,
// scene_mask.hpp; kernels crop_rect_count/scatter_masked) only the pixels it keeps.
CroppedPixels crop_pixels(ocl::Device& dev, const ocl::Buffer<float>& points,
                          const bp_camera& cam, const CropOptions& opt,
                          const ocl::Buffer<std::uint8_t>* mask = nullptr);
// Reference: the whole image, plain C++.
CroppedPixels crop_pixels_reference(const PointImage& points, const CropOptions& opt,
                                    const std::vector<std::uint8_t>* mask = nullptr);

}  // namespace binpick
