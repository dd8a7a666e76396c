// The per-pixel "may be used" mask of detection (--roi, --bin; kernels/scene_mask.cl): one byte
// a pixel, 1 where the pixel has data and its point lies inside every box of the region. The
// highest points, the crops and so the votes use only pixels the mask keeps.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "host/detect/scene/depth_to_points.hpp"
#include "host/runtime/cl/cl_buffer.hpp"
#include "kernels/scene_mask_shared.h"

namespace binpick {

// A box in its own frame: a camera-frame point p has box coordinates q = R (p - t); kept when
// lo <= q <= hi (bounds included).
struct RegionBox {
  Eigen::Matrix3f R = Eigen::Matrix3f::Identity();  // rows: the box's axes in the camera frame
  Eigen::Vector3f t = Eigen::Vector3f::Zero();      // the box frame's origin, camera frame (mm)
  Eigen::Vector3f lo = Eigen::Vector3f::Zero(), hi = Eigen::Vector3f::Zero();  // mm
};

// The bin's walls in the frame of SceneRegion::bin (kernels/scene_mask_shared.h, bp_walls): the
// points seen through one are not kept.
struct BinWalls {
  Eigen::Vector2f reach = Eigen::Vector2f::Zero();  // inner faces at x = +-reach[0], y = +-reach[1]
  float height = 0;                                // mm, floor to rim
  std::uint32_t sides = 0;  // bit 0: +x, 1: -x, 2: +y, 3: -y; the walls tested
};

struct SceneRegion {
  std::optional<RegionBox> roi;  // --roi
  std::optional<RegionBox> bin;  // the bin's interior within the margin (bin_fit.hpp)
  std::optional<BinWalls> walls;  // with bin: points seen through these walls are not kept
  bool active() const { return roi.has_value() || bin.has_value(); }
};

// The kernels' form. InputError for a box with a non-finite value.
bp_region to_shared(const SceneRegion& region);

// Routine: the scene_mask kernel over n float4 points on the device.
ocl::Buffer<std::uint8_t> scene_mask(ocl::Device& dev, const ocl::Buffer<float>& points,
                                     std::size_t n, const SceneRegion& region);
// The same on a host point image (uploads it, reads the mask back).
std::vector<std::uint8_t> scene_mask(ocl::Device& dev, const PointImage& points,
                                     const SceneRegion& region);
// Reference: the same predicate (bp_region_keeps) in plain C++; equal byte for byte.
std::vector<std::uint8_t> scene_mask_reference(const PointImage& points,
                                               const SceneRegion& region);

// Routine: the points the mask keeps, the others all 0 (no data), into out (n float4); enqueued
// without waiting.
void enqueue_masked_points(ocl::Device& dev, const ocl::Buffer<float>& points,
                           const ocl::Buffer<std::uint8_t>& mask, std::size_t n,
                           ocl::Buffer<float>& out);
// Reference.
PointImage masked_points_reference(const PointImage& points, const std::vector<std::uint8_t>& mask);

}  // namespace binpick
