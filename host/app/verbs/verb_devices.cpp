// `binpick devices`: the OpenCL and Vulkan devices found, and the ones binpick would use.
#include <CLI/CLI.hpp>
#include <iostream>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "host/runtime/cl/cl_device.hpp"
#include "host/app/verbs/verbs.hpp"
#include "host/core/error.hpp"
#include "host/runtime/vk/vk_context.hpp"

namespace binpick::cli {
namespace {

void run_devices() {
  std::optional<std::string> failure;
  std::cout << "OpenCL (kernels: features, hashing, voting)   [* = used; BINPICK_OPENCL_DEVICE]\n";
  try {
    for (const auto& d : ocl::list_devices())
      std::cout << fmt::format("  {} {} / {}  [{}, {}, {} compute units, {:.1f} GiB]\n",
                               d.chosen ? '*' : ' ', d.platform, d.name, d.type, d.version,
                               d.compute_units, double(d.global_memory) / (1ull << 30));
  } catch (const DeviceError& e) {
    std::cout << "  none\n";
    failure = e.what();
  }
  std::cout << "Vulkan (rendering of synthetic bins)   [* = used; BINPICK_VULKAN_DEVICE]\n";
  try {
    for (const auto& d : vkrt::list_devices())
      std::cout << fmt::format("  {} {}  [{}, Vulkan {}]\n", d.chosen ? '*' : ' ', d.name, d.type,
                               d.api_version);
  } catch (const DeviceError& e) {
    std::cout << "  none\n";
    failure = failure ? *failure + "; " + e.what() : e.what();
  }
  if (failure) throw DeviceError(*failure);
}

}  // namespace

void add_devices_verb(CLI::App& app) {
  auto* verb = app.add_subcommand("devices", "List the OpenCL and Vulkan devices binpick would use");
  verb->callback(run_devices);
}

}  // namespace binpick::cli
