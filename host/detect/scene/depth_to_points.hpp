// A depth image as BOP stores it: uint16 values, depth_mm = value * depth_scale, 0 = no data.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "host/runtime/cl/cl_device.hpp"
#include "kernels/binpick_shared.h"

namespace binpick {

struct DepthImage {
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint16_t> raw;  // row-major, width * height
};

// The same held elsewhere (a PNG's pixels, a numpy array): what detection reads, never copied.
struct DepthView {
  std::uint32_t width = 0, height = 0;
  std::span<const std::uint16_t> raw;  // row-major, width * height

  DepthView(std::uint32_t w, std::uint32_t h, std::span<const std::uint16_t> r)
      : width(w), height(h), raw(r) {}
  DepthView(const DepthImage& image) : width(image.width), height(image.height), raw(image.raw) {}
};

// Camera-frame points, one per pixel: xyz in mm and w = 1 where there is data, all 0 elsewhere.
struct PointImage {
  std::uint32_t width = 0, height = 0;
  std::vector<float> xyzw;  // 4 floats a pixel
};

// InputError unless the image has the camera's size and the camera positive focal lengths and
// depth scale.
void check_depth_camera(DepthView depth, const bp_camera& cam);

// Routine: the depth_to_points kernel on dev.
PointImage depth_to_points(ocl::Device& dev, DepthView depth, const bp_camera& cam);
// Reference: the same in plain C++.
PointImage depth_to_points_reference(DepthView depth, const bp_camera& cam);

}  // namespace binpick
