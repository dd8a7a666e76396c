// Turns OpenCL's error codes and the C++ bindings' cl::Error into binpick::DeviceError with the
// failing call and what we were doing.
#pragma once

#include <string>
#include <string_view>

#include <CL/opencl.hpp>

namespace binpick::ocl {

std::string error_name(cl_int code);  // e.g. "CL_OUT_OF_RESOURCES (-5)"

[[noreturn]] void rethrow(const cl::Error& e, std::string_view doing);

// Runs f(); a cl::Error becomes a DeviceError that says what was being done.
template <class F>
decltype(auto) guarded(std::string_view doing, F&& f) {
  try {
    return f();
  } catch (const cl::Error& e) {
    rethrow(e, doing);
  }
}

}  // namespace binpick::ocl
