#include "host/runtime/cl/cl_error.hpp"

#include "host/core/error.hpp"

namespace binpick::ocl {

std::string error_name(cl_int code) {
  const char* name = "unknown error";
  switch (code) {
#define BP_CASE(c) \
  case c:          \
    name = #c;     \
    break;
    BP_CASE(CL_DEVICE_NOT_FOUND) BP_CASE(CL_DEVICE_NOT_AVAILABLE) BP_CASE(CL_COMPILER_NOT_AVAILABLE)
    BP_CASE(CL_MEM_OBJECT_ALLOCATION_FAILURE) BP_CASE(CL_OUT_OF_RESOURCES) BP_CASE(CL_OUT_OF_HOST_MEMORY)
    BP_CASE(CL_BUILD_PROGRAM_FAILURE) BP_CASE(CL_INVALID_VALUE) BP_CASE(CL_INVALID_DEVICE)
    BP_CASE(CL_INVALID_PLATFORM) BP_CASE(CL_INVALID_CONTEXT) BP_CASE(CL_INVALID_COMMAND_QUEUE)
    BP_CASE(CL_INVALID_MEM_OBJECT) BP_CASE(CL_INVALID_BUFFER_SIZE) BP_CASE(CL_INVALID_PROGRAM)
    BP_CASE(CL_INVALID_PROGRAM_EXECUTABLE) BP_CASE(CL_INVALID_KERNEL_NAME) BP_CASE(CL_INVALID_KERNEL)
    BP_CASE(CL_INVALID_ARG_INDEX) BP_CASE(CL_INVALID_ARG_VALUE) BP_CASE(CL_INVALID_ARG_SIZE)
    BP_CASE(CL_INVALID_KERNEL_ARGS) BP_CASE(CL_INVALID_WORK_DIMENSION)
    BP_CASE(CL_INVALID_WORK_GROUP_SIZE) BP_CASE(CL_INVALID_WORK_ITEM_SIZE)
    BP_CASE(CL_INVALID_GLOBAL_OFFSET) BP_CASE(CL_INVALID_EVENT) BP_CASE(CL_INVALID_OPERATION)
    BP_CASE(CL_INVALID_BUILD_OPTIONS) BP_CASE(CL_INVALID_GLOBAL_WORK_SIZE)
    BP_CASE(CL_PLATFORM_NOT_FOUND_KHR)
#undef BP_CASE
  }
  return std::string(name) + " (" + std::to_string(code) + ")";
}

void rethrow(const cl::Error& e, std::string_view doing) {
  throw DeviceError("OpenCL: " + std::string(e.what()) + " failed with " + error_name(e.err()) +
                    " while " + std::string(doing));
}

}  // namespace binpick::ocl
