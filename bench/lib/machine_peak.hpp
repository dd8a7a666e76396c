// What the OpenCL device can do at best, measured once with plain kernels each bound by one
// resource (kernels/machine_peak.cl), so that each detection stage's throughput can be reported
// as a fraction of it: memory bandwidth (STREAM triad), floating point (FMA chains),
// integer ALU, and random lookups (gathers from a table out of cache and one in cache).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "host/runtime/cl/cl_device.hpp"

namespace binpick {

// Shapes of the kernels' chains (kernels/machine_peak.cl): lanes per work item and step.
inline constexpr std::uint32_t kPeakFmaLanes = 8 * 16;  // 8 float16 accumulators
inline constexpr std::uint32_t kPeakIntLanes = 8 * 16;  // 8 uint16 accumulators
// Work-group size of every launch: fixed, so PoCL compiles each kernel once (see
// ocl::launch_local); the global size is rounded up to a multiple of it.
inline constexpr std::size_t kPeakLocalSize = 64;

struct PeakOptions {
  // Stream triad: bytes of each of its three arrays. Well beyond the last-level cache, so the
  // triad streams from DRAM (32 MB of L3 on the development machine).
  std::size_t stream_bytes = std::size_t(64) << 20;
  // FMA and integer chains: work items x steps (x 128 lanes x 1 FMA or 2 integer ops). Short
  // launches (about 1.5 ms at 350 GFLOP/s): on a shared machine a short launch is more likely
  // to run undisturbed on both cores, and the best of many is the peak.
  std::size_t fma_items = std::size_t(1) << 14;
  std::uint32_t fma_iterations = 128;
  std::size_t int_items = std::size_t(1) << 14;
  std::uint32_t int_iterations = 128;
  // Gathers: a table out of cache (DRAM) and one that fits a core's L2; items x lookups each.
  std::size_t gather_table_bytes = std::size_t(64) << 20;
  std::size_t gather_cached_table_bytes = std::size_t(256) << 10;
  std::size_t gather_items = std::size_t(1) << 14;
  std::uint32_t gather_lookups = 64;
  std::size_t local_size = kPeakLocalSize;
  // Timed launches per kernel after one untimed warm-up (compilation, first touch of pages);
  // the fastest counts (a peak: interference only ever slows a launch down).
  int repetitions = 20;
  // Smoke runs: every size divided by 16, 2 repetitions. Its figures are not peaks (the stream
  // arrays then fit the cache).
  bool quick = false;
};

struct MachinePeak {
  std::string device;               // "platform / device"
  unsigned compute_units = 0;
  // STREAM triad, 10^9 bytes/s, counting 3 x 16 bytes per float4 (b and c read, a written) as
  // STREAM does: the write-allocate read of a is not counted (real traffic is up to 4/3 of it).
  double stream_gb_s = 0.0;
  double fma_gflop_s = 0.0;         // 2 flops per FMA
  double int_gop_s = 0.0;           // 32-bit integer xor and add, each one op
  double gather_glookup_s = 0.0;    // 10^9 random 4-byte loads/s, table of gather_table_bytes
  double gather_cached_glookup_s = 0.0;  // the same from a table of gather_cached_table_bytes
  double seconds = 0.0;             // wall time of the whole measurement, compilation included
  PeakOptions used;                 // the sizes measured (after `quick`)
};

// Throws InputError for absurd options (zero or beyond the device's allocation limit, more work
// than tens of seconds, a work group beyond the device's maximum).
void check_peak_options(ocl::Device& dev, const PeakOptions& opt);

// Runs each kernel on `dev` and times it (queue finish after each launch). About 1 s with the
// default options (0.1 s quick); nothing else should be running on the device's queue.
MachinePeak measure_machine_peak(ocl::Device& dev, const PeakOptions& opt = {});

// One line: "stream 25.1 GB/s, fma 180 GFLOP/s, ... (device, N compute units)".
std::string describe(const MachinePeak& peak);

// The kernels one launch each on `dev` with work groups of `local`, returning their outputs,
// and the same arithmetic in plain C++ (for the tests).
// peak_stream_triad: a = b + s c; b and c of equal size, a multiple of 4 (float4s).
std::vector<float> peak_stream_triad(ocl::Device& dev, std::span<const float> b,
                                     std::span<const float> c, float s,
                                     std::size_t local = kPeakLocalSize);
std::vector<float> peak_stream_triad_reference(std::span<const float> b,
                                               std::span<const float> c, float s);
// peak_fma: one float per item, the sum of its 128 lanes after `iterations` steps.
std::vector<float> peak_fma(ocl::Device& dev, std::size_t items, std::uint32_t iterations,
                            float mul, float add, std::size_t local = kPeakLocalSize);
std::vector<float> peak_fma_reference(std::size_t items, std::uint32_t iterations, float mul,
                                      float add);
// peak_int_ops: one uint per item, the wrapping sum of its 128 lanes.
std::vector<std::uint32_t> peak_int_ops(ocl::Device& dev, std::size_t items,
                                        std::uint32_t iterations, std::uint32_t x,
                                        std::uint32_t y, std::size_t local = kPeakLocalSize);
std::vector<std::uint32_t> peak_int_ops_reference(std::size_t items, std::uint32_t iterations,
                                                  std::uint32_t x, std::uint32_t y);
// peak_gather: one uint per item, the wrapping sum of its `lookups` table entries.
std::vector<std::uint32_t> peak_gather(ocl::Device& dev, std::span<const std::uint32_t> table,
                                       std::size_t items, std::uint32_t lookups,
                                       std::uint32_t seed, std::size_t local = kPeakLocalSize);
std::vector<std::uint32_t> peak_gather_reference(std::span<const std::uint32_t> table,
                                                 std::size_t items, std::uint32_t lookups,
                                                 std::uint32_t seed);
// The gather's index for key k in a table of `size` entries: the kernel's peak_hash, scaled
// to the size as floor(hash * size / 2^32).
std::uint32_t peak_gather_index(std::uint32_t key, std::uint32_t size);

}  // namespace binpick
