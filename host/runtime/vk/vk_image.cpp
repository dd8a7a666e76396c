#include "host/runtime/vk/vk_image.hpp"

#include <string>

#include "host/core/error.hpp"

namespace binpick::vkrt {

Image::Image(Context& ctx, std::uint32_t width, std::uint32_t height, vk::Format format,
             vk::ImageUsageFlags usage, vk::ImageAspectFlags aspect)
    : width_(width), height_(height), format_(format), aspect_(aspect) {
  try {
    image_ = ctx.device().createImage({.imageType = vk::ImageType::e2D,
                                       .format = format,
                                       .extent = {width, height, 1},
                                       .mipLevels = 1,
                                       .arrayLayers = 1,
                                       .samples = vk::SampleCountFlagBits::e1,
                                       .tiling = vk::ImageTiling::eOptimal,
                                       .usage = usage,
                                       .sharingMode = vk::SharingMode::eExclusive,
                                       .initialLayout = vk::ImageLayout::eUndefined});
    auto req = image_.getMemoryRequirements();
    memory_ = ctx.device().allocateMemory(
        {.allocationSize = req.size,
         .memoryTypeIndex =
             ctx.memory_type(req.memoryTypeBits, vk::MemoryPropertyFlagBits::eDeviceLocal)});
    image_.bindMemory(*memory_, 0);
    view_ = ctx.device().createImageView(
        {.image = *image_,
         .viewType = vk::ImageViewType::e2D,
         .format = format,
         .subresourceRange = {.aspectMask = aspect, .baseMipLevel = 0, .levelCount = 1,
                              .baseArrayLayer = 0, .layerCount = 1}});
  } catch (const vk::SystemError& e) {
    throw DeviceError("Vulkan: creating a " + std::to_string(width) + " x " +
                      std::to_string(height) + " image: " + e.what());
  }
}

void Image::record_copy_to(const vk::raii::CommandBuffer& cmd, vk::Buffer buffer, std::uint32_t x,
                           std::uint32_t y, std::uint32_t w, std::uint32_t h) const {
  vk::BufferImageCopy region{
      .bufferOffset = 0,
      .bufferRowLength = w,
      .bufferImageHeight = h,
      .imageSubresource = {.aspectMask = aspect_, .mipLevel = 0, .baseArrayLayer = 0,
                           .layerCount = 1},
      .imageOffset = {std::int32_t(x), std::int32_t(y), 0},
      .imageExtent = {w, h, 1}};
  cmd.copyImageToBuffer(*image_, vk::ImageLayout::eTransferSrcOptimal, buffer, region);
}

}  // namespace binpick::vkrt
