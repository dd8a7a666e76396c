// The OpenCL device the pipeline runs on: context, in-order queue and a per-process cache of
// programs built from the kernels/ sources embedded in the binary.
//
// Choice: the environment variable BINPICK_OPENCL_DEVICE, if set, selects the first device whose
// "platform / device" name contains it (case-insensitive); otherwise a PoCL CPU device is
// preferred, then any device.
#pragma once

#include <initializer_list>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include <CL/opencl.hpp>

namespace binpick::ocl {

struct DeviceInfo {
  std::string platform;
  std::string name;
  std::string version;     // CL_DEVICE_VERSION
  std::string type;        // "CPU", "GPU", ...
  unsigned compute_units = 0;
  unsigned long long global_memory = 0;
  bool chosen = false;     // the one binpick would use
};

// All devices of all platforms; throws DeviceError naming the Debian package when there is none.
std::vector<DeviceInfo> list_devices();

class Device {
 public:
  // The process-wide device, created on first use.
  static Device& shared();

  Device();  // chooses as described above
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  const cl::Context& context() const { return context_; }
  cl::CommandQueue& queue() { return queue_; }
  const cl::Device& device() const { return device_; }
  std::string description() const;

  // kernel_name from kernels/program_file, building (and caching) the program on first use.
  // A failed build throws DeviceError carrying the compiler's log.
  cl::Kernel kernel(std::string_view program_file, std::string_view kernel_name);

  // Builds (and caches) the programs of these kernels/ files now, so that a stage's first launch
  // is not charged for a compile: PoCL compiles a program in about a second the first time on a
  // machine (then loads it from its disk cache). Returns the seconds spent; 0 if every program
  // was built before in this process.
  double prebuild(std::initializer_list<std::string_view> program_files);

  // Builds OpenCL C source (label names it in errors); throws DeviceError with the build log.
  cl::Program build(std::string_view label, const std::string& source);

 private:
  const cl::Program& program(std::string_view program_file);

  cl::Platform platform_;
  cl::Device device_;
  cl::Context context_;
  cl::CommandQueue queue_;
  std::mutex programs_mutex_;
  std::map<std::string, cl::Program, std::less<>> programs_;
};

// The source of kernels/FILE with every `#include "x.h"` of another embedded file inlined
// (once), so the .cl files stay valid OpenCL C that an offline compiler can check with -I kernels.
std::string resolved_source(std::string_view program_file);

}  // namespace binpick::ocl
