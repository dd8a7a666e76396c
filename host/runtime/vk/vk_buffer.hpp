// A storage buffer in host-visible, coherent memory: on lavapipe all memory is host memory, and
// on a GPU this keeps the renderer's few transfers simple.
#pragma once

#include <cstring>
#include <span>
#include <vector>

#include "host/runtime/vk/vk_context.hpp"

namespace binpick::vkrt {

class Buffer {
 public:
  Buffer(Context& ctx, vk::DeviceSize bytes,
         vk::BufferUsageFlags usage = vk::BufferUsageFlagBits::eStorageBuffer |
                                      vk::BufferUsageFlagBits::eTransferSrc |
                                      vk::BufferUsageFlagBits::eTransferDst);
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  Buffer(Buffer&&) = default;
  ~Buffer();

  template <class T>
  static Buffer from(Context& ctx, std::span<const T> data) {
    Buffer b(ctx, data.size_bytes());
    if (!data.empty()) std::memcpy(b.mapped_, data.data(), data.size_bytes());
    return b;
  }
  template <class T>
  std::vector<T> read() const {
    std::vector<T> out(bytes_ / sizeof(T));
    std::memcpy(out.data(), mapped_, out.size() * sizeof(T));
    return out;
  }
  void* mapped() const { return mapped_; }
  vk::DeviceSize size() const { return bytes_; }
  vk::Buffer get() const { return *buffer_; }

 private:
  vk::DeviceSize bytes_;
  vk::raii::Buffer buffer_{nullptr};
  vk::raii::DeviceMemory memory_{nullptr};
  void* mapped_ = nullptr;
};

}  // namespace binpick::vkrt
