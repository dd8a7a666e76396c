// Per-part pixel statistics that compute shaders accumulate with atomics: how many pixels a
// part covers and their bounding box. Shared by the visible (bin_gbuffer.comp) and the
// unoccluded (bin_coverage.comp) passes.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "host/runtime/vk/vk_buffer.hpp"

namespace binpick {

// min x, min y, max x, max y (inclusive pixel indices); kEmptyBox when the part has no pixel.
using PixelBox = std::array<int, 4>;
inline constexpr PixelBox kEmptyBox{2147483647, 2147483647, -1, -1};

struct PartPixels {
  std::vector<std::uint32_t> count;
  std::vector<PixelBox> box;
  explicit PartPixels(std::size_t parts = 0) : count(parts, 0), box(parts, kEmptyBox) {}
  void add(std::size_t part, int x, int y);  // what the shaders do with atomics
};

// BOP's bounding box of a PixelBox, as bop_toolkit's calc_2d_bbox computes it from a mask:
// [min x, min y, max x - min x, max y - min y]; [-1, -1, -1, -1] when empty (calc_gt_info).
std::array<int, 4> bop_bbox(const PixelBox& box);

// The device side: a count buffer (uint a part) and a box buffer (4 int a part), initialised
// to zero counts and empty boxes, for the shaders to accumulate into.
class PartPixelBuffers {
 public:
  PartPixelBuffers(vkrt::Context& ctx, std::size_t parts);
  const vkrt::Buffer& counts() const { return counts_; }
  const vkrt::Buffer& boxes() const { return boxes_; }
  PartPixels read() const;

 private:
  std::size_t parts_;
  vkrt::Buffer counts_, boxes_;
};

}  // namespace binpick
