// Whether a depth image of a given size can be detected on at all on this machine: detection
// keeps several images' worth of per-pixel buffers (points, low-pass, normals, masks) on the
// OpenCL device, which on PoCL is host memory. An image too large for it is refused up front with
// its size and the memory it would need, rather than ending in an allocation failure or the
// kernel's out-of-memory killer part way through a batch.
#pragma once

#include <cstdint>

namespace binpick {

// Bytes detection needs for one width x height depth image, from measured peaks: about 120 MB
// of model, programs and runtime plus about 56 bytes a pixel (2064 x 1544 measured 300 MB,
// 1600 x 900 measured 202 MB); rounded up to 64 bytes a pixel and 160 MB.
std::uint64_t detect_memory_estimate(std::uint64_t width, std::uint64_t height);

// The machine's physical memory in bytes (0 if unknown).
std::uint64_t physical_memory_bytes();

// Throws InputError naming the image size and both amounts when the estimate exceeds
// `available` (default: the physical memory; unknown: no check).
void check_image_fits_in_memory(std::uint64_t width, std::uint64_t height,
                                std::uint64_t available = physical_memory_bytes());

}  // namespace binpick
