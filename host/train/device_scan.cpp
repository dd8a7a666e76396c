#include "host/train/device_scan.hpp"

#include <algorithm>
#include <string>

#include "host/core/error.hpp"

namespace binpick {

std::uint32_t exclusive_scan(ocl::Device& dev, const ocl::Buffer<std::uint32_t>& in,
                             std::size_t n, ocl::Buffer<std::uint32_t>& out) {
  if (in.size() < n || out.size() < n + 1)
    throw std::logic_error("exclusive_scan: buffers of " + std::to_string(in.size()) + " and " +
                           std::to_string(out.size()) + " elements for " + std::to_string(n));
  if (n > 0xffffffffu) throw InputError("exclusive_scan: more than 2^32 values");
  // Enough chunks to keep every core busy, each long enough to amortise a work item.
  const std::size_t blocks = std::clamp<std::size_t>(n / 4096, 1, 256);
  const auto chunk = static_cast<std::uint32_t>((n + blocks - 1) / std::max<std::size_t>(blocks, 1));
  const auto count = static_cast<std::uint32_t>(n);
  if (n == 0) {
    out.fill(dev, 0u);
    return 0;
  }
  ocl::Buffer<std::uint32_t> sums(dev, blocks + 1);
  cl::Kernel chunks = dev.kernel("device_scan.cl", "scan_chunks");
  cl::Kernel totals = dev.kernel("device_scan.cl", "scan_chunk_sums");
  cl::Kernel add = dev.kernel("device_scan.cl", "scan_add_offsets");
  // One work item per chunk, unpadded: a chunk past the last writes its (zero) sum.
  ocl::launch_tasks(dev, chunks, blocks, in, count, chunk, out, sums);
  ocl::launch(dev, totals, 1, sums, static_cast<std::uint32_t>(blocks), out, count);
  ocl::launch(dev, add, n, out, count, chunk, sums);
  return sums.read(dev).back();
}

std::vector<std::uint32_t> exclusive_scan_reference(const std::vector<std::uint32_t>& in) {
  std::vector<std::uint32_t> out(in.size() + 1, 0);
  for (std::size_t i = 0; i < in.size(); ++i) out[i + 1] = out[i] + in[i];
  return out;
}

}  // namespace binpick
