// Exclusive prefix sum of a device buffer of counts (kernels/device_scan.cl): the offsets of a CSR
// layout, or the output slots of a compaction. Shared by the PPF table and voxel subsampling.
#pragma once

#include <cstdint>
#include <vector>

#include "host/runtime/cl/cl_buffer.hpp"

namespace binpick {

// out[i] = in[0] + ... + in[i-1] for i <= n (out needs n + 1 elements; out[n] is the total,
// also returned). The caller guarantees that the total fits in 32 bits.
std::uint32_t exclusive_scan(ocl::Device& dev, const ocl::Buffer<std::uint32_t>& in,
                             std::size_t n, ocl::Buffer<std::uint32_t>& out);

// The same on the host: n + 1 values, the last one the total.
std::vector<std::uint32_t> exclusive_scan_reference(const std::vector<std::uint32_t>& in);

}  // namespace binpick
