#include "host/runtime/vk/vk_context.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include <spdlog/spdlog.h>

#include "host/core/error.hpp"

namespace binpick::vkrt {
namespace {

constexpr const char* kMissingDriver =
    "no Vulkan device found: install Debian's mesa-vulkan-drivers (lavapipe) and libvulkan1, "
    "or check BINPICK_VULKAN_DEVICE";
constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string version_string(std::uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
         "." + std::to_string(VK_API_VERSION_PATCH(v));
}

std::string type_name(vk::PhysicalDeviceType t) {
  switch (t) {
    case vk::PhysicalDeviceType::eCpu: return "CPU";
    case vk::PhysicalDeviceType::eIntegratedGpu: return "integrated GPU";
    case vk::PhysicalDeviceType::eDiscreteGpu: return "discrete GPU";
    case vk::PhysicalDeviceType::eVirtualGpu: return "virtual GPU";
    default: return "other";
  }
}

// A queue family able to do both graphics and compute, or -1.
int universal_family(const vk::raii::PhysicalDevice& p) {
  auto families = p.getQueueFamilyProperties();
  for (std::size_t i = 0; i < families.size(); ++i)
    if ((families[i].queueFlags & vk::QueueFlagBits::eGraphics) &&
        (families[i].queueFlags & vk::QueueFlagBits::eCompute))
      return int(i);
  return -1;
}

std::size_t choose(const std::vector<vk::raii::PhysicalDevice>& devices) {
  std::vector<std::size_t> usable;
  for (std::size_t i = 0; i < devices.size(); ++i)
    if (universal_family(devices[i]) >= 0) usable.push_back(i);
  if (usable.empty()) throw DeviceError(kMissingDriver);
  if (const char* want = std::getenv("BINPICK_VULKAN_DEVICE"); want && *want) {
    for (std::size_t i : usable)
      if (lower(devices[i].getProperties().deviceName.data()).find(lower(want)) != std::string::npos)
        return i;
    throw DeviceError(std::string("BINPICK_VULKAN_DEVICE='") + want +
                      "' matches no Vulkan device (see `binpick devices`)");
  }
  for (std::size_t i : usable)
    if (devices[i].getProperties().deviceType == vk::PhysicalDeviceType::eCpu) return i;
  return usable.front();
}

vk::raii::Instance make_instance(const vk::raii::Context& loader, bool validation) {
  vk::ApplicationInfo app{.pApplicationName = "binpick",
                          .applicationVersion = 1,
                          .pEngineName = "binpick",
                          .engineVersion = 1,
                          .apiVersion = VK_API_VERSION_1_1};
  std::vector<const char*> layers, extensions;
  if (validation) {
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  vk::InstanceCreateInfo info{.pApplicationInfo = &app,
                              .enabledLayerCount = std::uint32_t(layers.size()),
                              .ppEnabledLayerNames = layers.data(),
                              .enabledExtensionCount = std::uint32_t(extensions.size()),
                              .ppEnabledExtensionNames = extensions.data()};
  return vk::raii::Instance(loader, info);
}

bool has_validation_layer(const vk::raii::Context& loader) {
  for (const auto& l : loader.enumerateInstanceLayerProperties())
    if (std::string(l.layerName.data()) == kValidationLayer) return true;
  return false;
}

VKAPI_ATTR VkBool32 VKAPI_CALL on_validation(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data,
                                             void* user) {
  if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT)
    static_cast<Context*>(user)->report_validation(data->pMessage ? data->pMessage : "?");
  else if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT)
    spdlog::warn("Vulkan validation: {}", data->pMessage ? data->pMessage : "?");
  return VK_FALSE;
}

template <class F>
decltype(auto) guarded(const std::string& doing, F&& f) {
  try {
    return f();
  } catch (const vk::SystemError& e) {
    throw DeviceError("Vulkan: " + std::string(e.what()) + " while " + doing);
  }
}

}  // namespace

ContextOptions ContextOptions::from_environment() {
  const char* v = std::getenv("BINPICK_VK_VALIDATION");
  return {.validation = v && std::string(v) != "0" && *v};
}

std::vector<DeviceInfo> list_devices() {
  return guarded("listing Vulkan devices", [] {
    vk::raii::Context loader;
    vk::raii::Instance instance = make_instance(loader, false);
    vk::raii::PhysicalDevices devices(instance);
    std::size_t chosen = choose(devices);
    std::vector<DeviceInfo> out;
    for (std::size_t i = 0; i < devices.size(); ++i) {
      auto p = devices[i].getProperties();
      out.push_back({p.deviceName.data(), type_name(p.deviceType), version_string(p.apiVersion),
                     std::to_string(p.driverVersion), i == chosen});
    }
    return out;
  });
}

Context& Context::shared() {
  static Context context;
  return context;
}

Context::Context(const ContextOptions& options) {
  guarded("opening the Vulkan device", [&] {
    validation_ = options.validation;
    if (validation_ && !has_validation_layer(loader_))
      throw DeviceError(
          "Vulkan validation was requested but VK_LAYER_KHRONOS_validation is missing: install "
          "Debian's vulkan-validationlayers");
    instance_ = make_instance(loader_, validation_);
    if (validation_) {
      using S = vk::DebugUtilsMessageSeverityFlagBitsEXT;
      using T = vk::DebugUtilsMessageTypeFlagBitsEXT;
      messenger_ = instance_.createDebugUtilsMessengerEXT(
          {.messageSeverity = S::eWarning | S::eError,
           .messageType = T::eGeneral | T::eValidation | T::ePerformance,
           .pfnUserCallback = &on_validation,
           .pUserData = this});
    }
    vk::raii::PhysicalDevices devices(instance_);
    physical_ = std::move(devices[choose(devices)]);
    queue_family_ = std::uint32_t(universal_family(physical_));
    float priority = 1.0f;
    vk::DeviceQueueCreateInfo queue_info{
        .queueFamilyIndex = queue_family_, .queueCount = 1, .pQueuePriorities = &priority};
    device_ = vk::raii::Device(physical_, {.queueCreateInfoCount = 1, .pQueueCreateInfos = &queue_info});
    queue_ = device_.getQueue(queue_family_, 0);
    pool_ = device_.createCommandPool({.flags = vk::CommandPoolCreateFlagBits::eTransient,
                                       .queueFamilyIndex = queue_family_});
  });
}

std::string Context::description() const {
  auto p = physical_.getProperties();
  return std::string(p.deviceName.data()) + " (" + type_name(p.deviceType) + ", Vulkan " +
         version_string(p.apiVersion) + ")";
}

void Context::submit_and_wait(const std::function<void(const vk::raii::CommandBuffer&)>& record,
                              const std::string& what) {
  guarded(what, [&] {
    vk::raii::CommandBuffers buffers(device_, {.commandPool = *pool_,
                                               .level = vk::CommandBufferLevel::ePrimary,
                                               .commandBufferCount = 1});
    const vk::raii::CommandBuffer& cmd = buffers.front();
    cmd.begin({.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    record(cmd);
    cmd.end();
    vk::raii::Fence fence(device_, vk::FenceCreateInfo{});
    vk::CommandBuffer raw = *cmd;
    queue_.submit(vk::SubmitInfo{.commandBufferCount = 1, .pCommandBuffers = &raw}, *fence);
    if (device_.waitForFences(*fence, VK_TRUE, UINT64_MAX) != vk::Result::eSuccess)
      throw DeviceError("Vulkan: waiting for " + what + " failed");
  });
  check_validation(what);
}

std::uint32_t Context::memory_type(std::uint32_t type_bits, vk::MemoryPropertyFlags required) const {
  auto props = physical_.getMemoryProperties();
  for (std::uint32_t i = 0; i < props.memoryTypeCount; ++i)
    if ((type_bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & required) == required)
      return i;
  throw DeviceError("Vulkan: no memory type with the required properties");
}

void Context::report_validation(std::string message) {
  std::lock_guard lock(messages_mutex_);
  messages_.push_back(std::move(message));
}

void Context::check_validation(const std::string& what) {
  std::lock_guard lock(messages_mutex_);
  if (messages_.empty()) return;
  std::string all = "Vulkan validation errors while " + what + ":";
  for (const auto& m : messages_) all += "\n  " + m;
  messages_.clear();
  throw DeviceError(all);
}

}  // namespace binpick::vkrt
