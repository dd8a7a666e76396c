// A typed device buffer and a kernel launch whose argument index is the argument's position.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <CL/opencl.hpp>

#include "host/runtime/cl/cl_device.hpp"
#include "host/runtime/cl/cl_error.hpp"

namespace binpick::ocl {

template <class T>
class Buffer {
 public:
  Buffer() = default;
  // OpenCL forbids zero-sized buffers; an empty buffer still holds one element of storage.
  Buffer(Device& dev, std::size_t count, cl_mem_flags flags = CL_MEM_READ_WRITE)
      : count_(count) {
    buffer_ = guarded("allocating a buffer of " + std::to_string(count) + " elements", [&] {
      return cl::Buffer(dev.context(), flags, sizeof(T) * std::max<std::size_t>(count, 1));
    });
  }
  Buffer(Device& dev, std::span<const T> host, cl_mem_flags flags = CL_MEM_READ_WRITE)
      : Buffer(dev, host.size(), flags) {
    write(dev, host);
  }

  void write(Device& dev, std::span<const T> host) {
    if (host.empty()) return;
    guarded("writing a buffer", [&] {
      dev.queue().enqueueWriteBuffer(buffer_, CL_TRUE, 0, sizeof(T) * host.size(), host.data());
    });
  }
  void fill(Device& dev, const T& value) {
    guarded("filling a buffer", [&] {
      dev.queue().enqueueFillBuffer(buffer_, value, 0, sizeof(T) * std::max<std::size_t>(count_, 1));
    });
  }
  std::vector<T> read(Device& dev, std::size_t count) const {
    std::vector<T> host(count);
    if (count == 0) return host;
    guarded("reading a buffer", [&] {
      dev.queue().enqueueReadBuffer(buffer_, CL_TRUE, 0, sizeof(T) * count, host.data());
    });
    return host;
  }
  std::vector<T> read(Device& dev) const { return read(dev, count_); }
  // A buffer of its own with the same contents (a copy shares the device memory).
  Buffer clone(Device& dev) const {
    Buffer copy(dev, count_);
    guarded("copying a buffer", [&] {
      dev.queue().enqueueCopyBuffer(buffer_, copy.buffer_, 0, 0,
                                    sizeof(T) * std::max<std::size_t>(count_, 1));
    });
    return copy;
  }

  std::size_t size() const { return count_; }
  const cl::Buffer& get() const { return buffer_; }

 private:
  cl::Buffer buffer_;
  std::size_t count_ = 0;
};

namespace detail {
template <class T>
const cl::Buffer& arg(const Buffer<T>& b) { return b.get(); }
template <class T>
const T& arg(const T& v) { return v; }
}  // namespace detail

// Like launch, with work groups of `local` work items: the global size is rounded up to a
// multiple of it, and kernels guard their tail (`if (i >= n) return;`, never the global size).
// PoCL compiles a kernel once per work-group size; left to choose (cl::NullRange) it derives the
// size from the global size, so a kernel launched on sizes that change every call (a crop, the
// poses of one hypothesis) is compiled again for each new size, ~100 ms each on a fresh machine.
// A fixed local size compiles once.
template <class... Args>
void launch_local(Device& dev, cl::Kernel& kernel, std::size_t global, std::size_t local,
                  const Args&... args) {
  if (global == 0) return;
  if (local == 0) local = 1;
  const std::size_t padded = (global + local - 1) / local * local;
  const std::string name = kernel.getInfo<CL_KERNEL_FUNCTION_NAME>();
  guarded("launching kernel " + name, [&] {
    cl_uint index = 0;
    try {
      ((kernel.setArg(index, detail::arg(args)), ++index), ...);
    } catch (const cl::Error& e) {
      rethrow(e, "binding argument " + std::to_string(index) + " of kernel " + name);
    }
    dev.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(padded),
                                     cl::NDRange(local));
  });
}

// The work-group size of launch: one size for every kernel and every global size (see above).
inline constexpr std::size_t kWorkGroupSize = 64;

// Binds args to kernel parameters 0, 1, 2, ... and runs `global` work items (none if 0), in work
// groups of kWorkGroupSize.
template <class... Args>
void launch(Device& dev, cl::Kernel& kernel, std::size_t global, const Args&... args) {
  launch_local(dev, kernel, global, kWorkGroupSize, args...);
}

// Like launch, with one work item per work group: for work items that are independent tasks of
// uneven cost (one reference point's voting each). Left to itself PoCL may put a few hundred of
// them in one work group, which runs on one core.
template <class... Args>
void launch_tasks(Device& dev, cl::Kernel& kernel, std::size_t global, const Args&... args) {
  launch_local(dev, kernel, global, 1, args...);
}

inline void finish(Device& dev) {
  guarded("waiting for the OpenCL queue", [&] { dev.queue().finish(); });
}

}  // namespace binpick::ocl
