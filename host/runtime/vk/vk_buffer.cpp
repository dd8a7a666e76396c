#include "host/runtime/vk/vk_buffer.hpp"

#include <algorithm>

namespace binpick::vkrt {

Buffer::Buffer(Context& ctx, vk::DeviceSize bytes, vk::BufferUsageFlags usage)
    : bytes_(bytes) {
  // Vulkan forbids empty buffers; keep one word of storage for an empty one.
  buffer_ = ctx.device().createBuffer(
      {.size = std::max<vk::DeviceSize>(bytes, 4), .usage = usage,
       .sharingMode = vk::SharingMode::eExclusive});
  auto req = buffer_.getMemoryRequirements();
  memory_ = ctx.device().allocateMemory(
      {.allocationSize = req.size,
       .memoryTypeIndex = ctx.memory_type(req.memoryTypeBits,
                                          vk::MemoryPropertyFlagBits::eHostVisible |
                                              vk::MemoryPropertyFlagBits::eHostCoherent)});
  buffer_.bindMemory(*memory_, 0);
  mapped_ = memory_.mapMemory(0, VK_WHOLE_SIZE);
}

Buffer::~Buffer() {
  if (mapped_ && *memory_) memory_.unmapMemory();
}

}  // namespace binpick::vkrt
