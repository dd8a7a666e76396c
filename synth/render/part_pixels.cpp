#include "synth/render/part_pixels.hpp"

#include <algorithm>
#include <cstring>

namespace binpick {

void PartPixels::add(std::size_t part, int x, int y) {
  ++count[part];
  PixelBox& b = box[part];
  b = {std::min(b[0], x), std::min(b[1], y), std::max(b[2], x), std::max(b[3], y)};
}

std::array<int, 4> bop_bbox(const PixelBox& b) {
  if (b[2] < b[0] || b[3] < b[1]) return {-1, -1, -1, -1};
  return {b[0], b[1], b[2] - b[0], b[3] - b[1]};
}

PartPixelBuffers::PartPixelBuffers(vkrt::Context& ctx, std::size_t parts)
    : parts_(parts),
      counts_(ctx, parts * sizeof(std::uint32_t)),
      boxes_(ctx, parts * sizeof(PixelBox)) {
  if (parts == 0) return;
  std::memset(counts_.mapped(), 0, parts * sizeof(std::uint32_t));
  std::vector<PixelBox> empty(parts, kEmptyBox);
  std::memcpy(boxes_.mapped(), empty.data(), parts * sizeof(PixelBox));
}

PartPixels PartPixelBuffers::read() const {
  PartPixels out(parts_);
  if (parts_ == 0) return out;
  std::memcpy(out.count.data(), counts_.mapped(), parts_ * sizeof(std::uint32_t));
  std::memcpy(out.box.data(), boxes_.mapped(), parts_ * sizeof(PixelBox));
  return out;
}

}  // namespace binpick
