#include "host/runtime/cl/cl_device.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>

#include "host/runtime/cl/cl_error.hpp"
#include "host/core/error.hpp"
#include "host/core/timing.hpp"

namespace binpick::ocl {
namespace {

constexpr const char* kMissingDriver =
    "no OpenCL device found: install Debian's pocl-opencl-icd (the PoCL CPU driver) and "
    "ocl-icd-libopencl1, or check BINPICK_OPENCL_DEVICE";

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string type_name(cl_device_type t) {
  if (t & CL_DEVICE_TYPE_CPU) return "CPU";
  if (t & CL_DEVICE_TYPE_GPU) return "GPU";
  if (t & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  return "other";
}

struct Candidate {
  cl::Platform platform;
  cl::Device device;
};

std::vector<Candidate> all_candidates() {
  std::vector<cl::Platform> platforms;
  // The ICD loader reports "no platform" as an error code rather than an empty list.
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error&) {
    platforms.clear();
  }
  std::vector<Candidate> out;
  for (auto& p : platforms) {
    std::vector<cl::Device> devices;
    try {
      p.getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error&) {
      continue;  // a platform with no device of any type
    }
    for (auto& d : devices) out.push_back({p, d});
  }
  return out;
}

std::size_t choose(const std::vector<Candidate>& c) {
  if (c.empty()) throw DeviceError(kMissingDriver);
  if (const char* want = std::getenv("BINPICK_OPENCL_DEVICE"); want && *want) {
    for (std::size_t i = 0; i < c.size(); ++i) {
      std::string full = c[i].platform.getInfo<CL_PLATFORM_NAME>() + " / " +
                         c[i].device.getInfo<CL_DEVICE_NAME>();
      if (lower(full).find(lower(want)) != std::string::npos) return i;
    }
    throw DeviceError(std::string("BINPICK_OPENCL_DEVICE='") + want +
                      "' matches no OpenCL device (see `binpick devices`)");
  }
  for (std::size_t i = 0; i < c.size(); ++i)
    if (lower(c[i].platform.getInfo<CL_PLATFORM_NAME>()).find("portable computing") !=
            std::string::npos &&
        (c[i].device.getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_CPU))
      return i;
  return 0;
}

}  // namespace

std::vector<DeviceInfo> list_devices() {
  return guarded("listing OpenCL devices", [] {
    auto c = all_candidates();
    std::size_t chosen = choose(c);
    std::vector<DeviceInfo> out;
    for (std::size_t i = 0; i < c.size(); ++i) {
      const cl::Device& d = c[i].device;
      out.push_back({c[i].platform.getInfo<CL_PLATFORM_NAME>(), d.getInfo<CL_DEVICE_NAME>(),
                     d.getInfo<CL_DEVICE_VERSION>(), type_name(d.getInfo<CL_DEVICE_TYPE>()),
                     d.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>(),
                     static_cast<unsigned long long>(d.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>()),
                     i == chosen});
    }
    return out;
  });
}

Device& Device::shared() {
  static Device device;  // thread-safe initialisation; lives until exit
  return device;
}

Device::Device() {
  guarded("opening the OpenCL device", [this] {
    auto c = all_candidates();
    const Candidate& pick = c[choose(c)];
    platform_ = pick.platform;
    device_ = pick.device;
    context_ = cl::Context(device_);
    queue_ = cl::CommandQueue(context_, device_, CL_QUEUE_PROFILING_ENABLE);
  });
}

std::string Device::description() const {
  return platform_.getInfo<CL_PLATFORM_NAME>() + " / " + device_.getInfo<CL_DEVICE_NAME>();
}

cl::Program Device::build(std::string_view label, const std::string& source) {
  cl::Program program = guarded("creating program " + std::string(label),
                                [&] { return cl::Program(context_, source); });
  try {
    // No fast-math: kernels must agree with their C++ references up to rounding.
    program.build({device_}, "-cl-std=CL1.2");
  } catch (const cl::Error& e) {
    std::string log;
    try {
      log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device_);
    } catch (const cl::Error&) {
      log = "(no build log)";
    }
    throw DeviceError("OpenCL: building " + std::string(label) + " failed with " +
                      error_name(e.err()) + ":\n" + log);
  }
  return program;
}

const cl::Program& Device::program(std::string_view program_file) {
  std::lock_guard lock(programs_mutex_);
  if (auto it = programs_.find(program_file); it != programs_.end()) return it->second;
  cl::Program program = build("kernels/" + std::string(program_file), resolved_source(program_file));
  return programs_.emplace(std::string(program_file), std::move(program)).first->second;
}

double Device::prebuild(std::initializer_list<std::string_view> program_files) {
  const auto start = std::chrono::steady_clock::now();
  bool built = false;
  for (std::string_view file : program_files) {
    {
      std::lock_guard lock(programs_mutex_);
      if (programs_.find(file) != programs_.end()) continue;
    }
    program(file);
    built = true;
  }
  return built ? seconds_since(start) : 0.0;
}

cl::Kernel Device::kernel(std::string_view program_file, std::string_view kernel_name) {
  const cl::Program& p = program(program_file);
  return guarded("creating kernel " + std::string(kernel_name) + " of kernels/" +
                     std::string(program_file),
                 [&] { return cl::Kernel(p, std::string(kernel_name).c_str()); });
}

}  // namespace binpick::ocl
