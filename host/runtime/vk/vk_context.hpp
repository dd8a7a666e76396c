// The Vulkan device the renderer runs on: a headless instance, one queue that does graphics
// and compute, a command pool, and the validation layer's complaints turned into errors.
//
// Choice: BINPICK_VULKAN_DEVICE (a case-insensitive substring of the device name) if set;
// otherwise a CPU device (Mesa's lavapipe: same pictures on every machine), then any device.
// BINPICK_VK_VALIDATION=1 enables VK_LAYER_KHRONOS_validation (Debian: vulkan-validationlayers).
#pragma once

#include <functional>
#include <mutex>
#include <string>
#include <vector>

#ifndef VULKAN_HPP_NO_CONSTRUCTORS  // designated initialisers for Vulkan structs (also set by CMake)
#define VULKAN_HPP_NO_CONSTRUCTORS
#endif
#include <vulkan/vulkan_raii.hpp>

namespace binpick::vkrt {

struct DeviceInfo {
  std::string name;
  std::string type;  // "CPU", "integrated GPU", ...
  std::string api_version;
  std::string driver;
  bool chosen = false;
};

// All physical devices; throws DeviceError naming the Debian package when there is none.
std::vector<DeviceInfo> list_devices();

struct ContextOptions {
  bool validation = false;  // default from BINPICK_VK_VALIDATION
  static ContextOptions from_environment();
};

class Context {
 public:
  static Context& shared();  // created on first use with options from the environment
  explicit Context(const ContextOptions& options = ContextOptions::from_environment());
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  const vk::raii::Device& device() const { return device_; }
  const vk::raii::PhysicalDevice& physical() const { return physical_; }
  const vk::raii::Queue& queue() const { return queue_; }
  std::uint32_t queue_family() const { return queue_family_; }
  std::string description() const;
  bool validation_enabled() const { return validation_; }

  // Records with `record` into a one-time command buffer, submits, waits, then throws
  // DeviceError if the validation layer reported an error meanwhile.
  void submit_and_wait(const std::function<void(const vk::raii::CommandBuffer&)>& record,
                       const std::string& what);

  // Memory type with `required` properties among `type_bits`; throws if none.
  std::uint32_t memory_type(std::uint32_t type_bits, vk::MemoryPropertyFlags required) const;

  // Throws DeviceError with the validation messages collected so far (and clears them).
  void check_validation(const std::string& what);
  void report_validation(std::string message);  // called from the debug messenger

 private:
  vk::raii::Context loader_;
  vk::raii::Instance instance_{nullptr};
  vk::raii::DebugUtilsMessengerEXT messenger_{nullptr};
  vk::raii::PhysicalDevice physical_{nullptr};
  vk::raii::Device device_{nullptr};
  vk::raii::Queue queue_{nullptr};
  vk::raii::CommandPool pool_{nullptr};
  std::uint32_t queue_family_ = 0;
  bool validation_ = false;
  std::mutex messages_mutex_;
  std::vector<std::string> messages_;
};

}  // namespace binpick::vkrt
