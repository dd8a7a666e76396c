// A 2D image in device-local memory with one view: the renderer's attachments. They are read
// back with vkCmdCopyImageToBuffer into a host-visible Buffer, never mapped.
#pragma once

#include <cstdint>

#include "host/runtime/vk/vk_context.hpp"

namespace binpick::vkrt {

class Image {
 public:
  // aspect: eColor, or eDepth for a depth format. One mip level, one layer, optimal tiling.
  Image(Context& ctx, std::uint32_t width, std::uint32_t height, vk::Format format,
        vk::ImageUsageFlags usage, vk::ImageAspectFlags aspect);
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;
  Image(Image&&) = default;

  vk::Image get() const { return *image_; }
  vk::ImageView view() const { return *view_; }
  vk::Format format() const { return format_; }
  vk::ImageAspectFlags aspect() const { return aspect_; }
  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }

  // Records a copy of the rectangle (x, y, w, h) into `buffer` at offset 0, tightly packed
  // (row length w). The image must be in eTransferSrcOptimal.
  void record_copy_to(const vk::raii::CommandBuffer& cmd, vk::Buffer buffer, std::uint32_t x,
                      std::uint32_t y, std::uint32_t w, std::uint32_t h) const;

 private:
  std::uint32_t width_, height_;
  vk::Format format_;
  vk::ImageAspectFlags aspect_;
  vk::raii::Image image_{nullptr};
  vk::raii::DeviceMemory memory_{nullptr};
  vk::raii::ImageView view_{nullptr};
};

}  // namespace binpick::vkrt
