// The OpenCL device the tests run their kernels on: the one binpick itself would choose
// (BINPICK_OPENCL_DEVICE selects another, so the parity tests can be run on every device).
#pragma once

#include "host/runtime/cl/cl_device.hpp"

namespace binpick::test {

inline ocl::Device& test_device() { return ocl::Device::shared(); }

}  // namespace binpick::test
