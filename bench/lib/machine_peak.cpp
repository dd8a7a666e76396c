#include "bench/lib/machine_peak.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "host/runtime/cl/cl_buffer.hpp"
#include "host/core/error.hpp"
#include "host/core/timing.hpp"

namespace binpick {
namespace {

constexpr const char* kProgram = "machine_peak.cl";
// Work items index with a uint and the padded global size must fit it too.
constexpr std::size_t kMaxItems = std::size_t(1) << 31;
// Beyond these a single launch runs for tens of seconds: a typo, not a measurement.
constexpr unsigned long long kMaxChainSteps = 1ull << 34;  // items x iterations (x 128 lanes)
constexpr unsigned long long kMaxLookups = 1ull << 34;     // items x lookups

[[noreturn]] void bad(const std::string& what) { throw InputError("machine peak: " + what); }

void check_range(const char* name, unsigned long long v, unsigned long long lo,
                 unsigned long long hi) {
  if (v < lo || v > hi)
    bad(std::string(name) + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) +
        "], not " + std::to_string(v));
}

unsigned long long max_alloc(ocl::Device& dev) {
  return ocl::guarded("querying the device's allocation limit", [&] {
    return static_cast<unsigned long long>(dev.device().getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>());
  });
}

void check_local(ocl::Device& dev, std::size_t local) {
  const auto max_wg = ocl::guarded("querying the device's work-group limit", [&] {
    return dev.device().getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
  });
  check_range("local_size", local, 1, max_wg);
}

void check_steps(const char* items_name, std::size_t items, const char* steps_name,
                 std::uint32_t steps, unsigned long long max_product) {
  check_range(items_name, items, 1, kMaxItems);
  check_range(steps_name, steps, 1, std::numeric_limits<std::uint32_t>::max());
  if (static_cast<unsigned long long>(items) * steps > max_product)
    bad(std::string(items_name) + " x " + steps_name + " must be at most " +
        std::to_string(max_product) + ", not " + std::to_string(items) + " x " +
        std::to_string(steps));
}

PeakOptions shrunk(PeakOptions o) {
  o.stream_bytes = std::max<std::size_t>(o.stream_bytes / 16, 16);
  o.fma_iterations = std::max<std::uint32_t>(o.fma_iterations / 16, 1);
  o.int_iterations = std::max<std::uint32_t>(o.int_iterations / 16, 1);
  o.gather_table_bytes = std::max<std::size_t>(o.gather_table_bytes / 16, 4);
  o.gather_cached_table_bytes = std::max<std::size_t>(o.gather_cached_table_bytes / 16, 4);
  o.gather_items = std::max<std::size_t>(o.gather_items / 16, 1);
  o.repetitions = std::min(o.repetitions, 2);
  return o;
}

// Seconds of the fastest of `reps` launches, each waited for, after one untimed warm-up launch
// (PoCL compiles the kernel for this work-group size on the first; pages are touched).
template <class Launch>
double best_seconds(ocl::Device& dev, int reps, Launch&& launch) {
  launch();
  ocl::finish(dev);
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < reps; ++r) {
    Stopwatch watch;
    launch();
    ocl::finish(dev);
    best = std::min(best, watch.lap() / 1e3);
  }
  return best;
}

// Lookups per second of peak_gather over a table of `bytes` (whole uints).
double gather_rate(ocl::Device& dev, const PeakOptions& o, std::size_t bytes) {
  const std::size_t size = bytes / 4;
  ocl::Buffer<std::uint32_t> table(dev, size, CL_MEM_READ_ONLY), out(dev, o.gather_items);
  table.fill(dev, 1u);  // contents do not matter to the timing; the fill touches the pages
  cl::Kernel k = dev.kernel(kProgram, "peak_gather");
  const double s = best_seconds(dev, o.repetitions, [&] {
    ocl::launch_local(dev, k, o.gather_items, o.local_size, table, cl_uint(size),
                      cl_uint(o.gather_items), cl_uint(o.gather_lookups), cl_uint(0), out);
  });
  return double(o.gather_items) * o.gather_lookups / s;
}

void check_items(std::size_t items) { check_range("items", items, 0, kMaxItems); }

void check_triad(std::span<const float> b, std::span<const float> c) {
  if (b.size() != c.size() || b.size() % 4 != 0)
    bad("stream triad inputs must be of equal size, a multiple of 4 floats, not " +
        std::to_string(b.size()) + " and " + std::to_string(c.size()));
}

}  // namespace

void check_peak_options(ocl::Device& dev, const PeakOptions& o) {
  const unsigned long long alloc = max_alloc(dev);
  check_range("repetitions", o.repetitions < 0 ? 0 : unsigned(o.repetitions), 1, 1000);
  check_local(dev, o.local_size);
  // float4 elements are indexed with a uint; table entries too (mul_hi by the size).
  check_range("stream_bytes", o.stream_bytes, 16, std::min(alloc, 16ull * 0xffffffffull));
  check_range("gather_table_bytes", o.gather_table_bytes, 4, std::min(alloc, 4ull * 0xffffffffull));
  check_range("gather_cached_table_bytes", o.gather_cached_table_bytes, 4,
              std::min(alloc, 4ull * 0xffffffffull));
  check_steps("fma_items", o.fma_items, "fma_iterations", o.fma_iterations, kMaxChainSteps);
  check_steps("int_items", o.int_items, "int_iterations", o.int_iterations, kMaxChainSteps);
  check_steps("gather_items", o.gather_items, "gather_lookups", o.gather_lookups, kMaxLookups);
}

MachinePeak measure_machine_peak(ocl::Device& dev, const PeakOptions& options) {
  check_peak_options(dev, options);
  Stopwatch total;
  const PeakOptions o = options.quick ? shrunk(options) : options;
  MachinePeak p;
  p.device = dev.description();
  p.compute_units = ocl::guarded("querying the device's compute units", [&] {
    return unsigned(dev.device().getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>());
  });
  p.used = o;
  {  // buffers scoped: the 3 x 64 MB are freed before the next kernel
    const std::size_t n = o.stream_bytes / 16;  // float4s
    ocl::Buffer<float> a(dev, 4 * n), b(dev, 4 * n, CL_MEM_READ_ONLY), c(dev, 4 * n, CL_MEM_READ_ONLY);
    a.fill(dev, 0.0f), b.fill(dev, 1.0f), c.fill(dev, 2.0f);
    cl::Kernel k = dev.kernel(kProgram, "peak_stream_triad");
    const double s = best_seconds(dev, o.repetitions, [&] {
      ocl::launch_local(dev, k, n, o.local_size, a, b, c, 3.0f, cl_uint(n));
    });
    p.stream_gb_s = 3.0 * 16.0 * double(n) / s / 1e9;
  }
  {  // 0.999 x + 0.001 converges to 1: no overflow, no denormals
    ocl::Buffer<float> out(dev, o.fma_items);
    cl::Kernel k = dev.kernel(kProgram, "peak_fma");
    const double s = best_seconds(dev, o.repetitions, [&] {
      ocl::launch_local(dev, k, o.fma_items, o.local_size, out, cl_uint(o.fma_items),
                        cl_uint(o.fma_iterations), 0.999f, 0.001f);
    });
    p.fma_gflop_s = 2.0 * double(o.fma_items) * o.fma_iterations * kPeakFmaLanes / s / 1e9;
  }
  {
    ocl::Buffer<std::uint32_t> out(dev, o.int_items);
    cl::Kernel k = dev.kernel(kProgram, "peak_int_ops");
    const double s = best_seconds(dev, o.repetitions, [&] {
      ocl::launch_local(dev, k, o.int_items, o.local_size, out, cl_uint(o.int_items),
                        cl_uint(o.int_iterations), cl_uint(0x9e3779b9u), cl_uint(0x7f4a7c15u));
    });
    p.int_gop_s = 2.0 * double(o.int_items) * o.int_iterations * kPeakIntLanes / s / 1e9;
  }
  p.gather_glookup_s = gather_rate(dev, o, o.gather_table_bytes) / 1e9;
  p.gather_cached_glookup_s = gather_rate(dev, o, o.gather_cached_table_bytes) / 1e9;
  p.seconds = total.lap() / 1e3;
  return p;
}

std::string describe(const MachinePeak& p) {
  char line[512];
  std::snprintf(line, sizeof line,
                "stream triad %.1f GB/s, fma %.1f GFLOP/s, int %.1f Gop/s, gather %.3f Glookup/s "
                "(%zu MB table), %.3f Glookup/s (%zu KB table)%s on %s, %u compute units, %.2f s",
                p.stream_gb_s, p.fma_gflop_s, p.int_gop_s, p.gather_glookup_s,
                p.used.gather_table_bytes >> 20, p.gather_cached_glookup_s,
                p.used.gather_cached_table_bytes >> 10, p.used.quick ? " [quick: not peaks]" : "",
                p.device.c_str(), p.compute_units, p.seconds);
  return line;
}

// ---- single launches and their references --------------------------------------------------

std::vector<float> peak_stream_triad(ocl::Device& dev, std::span<const float> b,
                                     std::span<const float> c, float s, std::size_t local) {
  check_triad(b, c);
  check_local(dev, local);
  const std::size_t n = b.size() / 4;
  check_items(n);
  ocl::Buffer<float> db(dev, b, CL_MEM_READ_ONLY), dc(dev, c, CL_MEM_READ_ONLY), da(dev, b.size());
  cl::Kernel k = dev.kernel(kProgram, "peak_stream_triad");
  ocl::launch_local(dev, k, n, local, da, db, dc, s, cl_uint(n));
  return da.read(dev);
}

std::vector<float> peak_stream_triad_reference(std::span<const float> b,
                                               std::span<const float> c, float s) {
  check_triad(b, c);
  std::vector<float> a(b.size());
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = std::fma(s, c[i], b[i]);
  return a;
}

std::vector<float> peak_fma(ocl::Device& dev, std::size_t items, std::uint32_t iterations,
                            float mul, float add, std::size_t local) {
  check_local(dev, local);
  check_items(items);
  ocl::Buffer<float> out(dev, items);
  cl::Kernel k = dev.kernel(kProgram, "peak_fma");
  ocl::launch_local(dev, k, items, local, out, cl_uint(items), cl_uint(iterations), mul, add);
  return out.read(dev);
}

std::vector<float> peak_fma_reference(std::size_t items, std::uint32_t iterations, float mul,
                                      float add) {
  std::vector<float> out(items);
  for (std::size_t i = 0; i < items; ++i) {
    const float x = float(i & 1023u) * (1.0f / 1024.0f);
    float c[8][16];  // [chain][lane], as the kernel's c0..c7
    for (int k = 0; k < 8; ++k)
      for (int l = 0; l < 16; ++l)
        c[k][l] = k == 0 ? x + float(l) : (x + float(l)) + float(16 * k);
    for (std::uint32_t t = 0; t < iterations; ++t)
      for (auto& chain : c)
        for (float& v : chain) v = std::fma(v, mul, add);
    float s[16], h[8], q[4];
    for (int l = 0; l < 16; ++l)
      s[l] = ((c[0][l] + c[1][l]) + (c[2][l] + c[3][l])) + ((c[4][l] + c[5][l]) + (c[6][l] + c[7][l]));
    for (int l = 0; l < 8; ++l) h[l] = s[l] + s[l + 8];  // .lo + .hi
    for (int l = 0; l < 4; ++l) q[l] = h[l] + h[l + 4];
    out[i] = (q[0] + q[2]) + (q[1] + q[3]);
  }
  return out;
}

std::vector<std::uint32_t> peak_int_ops(ocl::Device& dev, std::size_t items,
                                        std::uint32_t iterations, std::uint32_t x,
                                        std::uint32_t y, std::size_t local) {
  check_local(dev, local);
  check_items(items);
  ocl::Buffer<std::uint32_t> out(dev, items);
  cl::Kernel k = dev.kernel(kProgram, "peak_int_ops");
  ocl::launch_local(dev, k, items, local, out, cl_uint(items), cl_uint(iterations), cl_uint(x),
                    cl_uint(y));
  return out.read(dev);
}

std::vector<std::uint32_t> peak_int_ops_reference(std::size_t items, std::uint32_t iterations,
                                                  std::uint32_t x, std::uint32_t y) {
  std::vector<std::uint32_t> out(items);
  for (std::size_t i = 0; i < items; ++i) {
    std::uint32_t sum = 0;  // wrapping: the kernel's order of additions does not matter
    for (std::uint32_t lane = 0; lane < kPeakIntLanes; ++lane) {
      std::uint32_t v = 128u * std::uint32_t(i) + lane;
      for (std::uint32_t t = 0; t < iterations; ++t) v = (v ^ x) + y;
      sum += v;
    }
    out[i] = sum;
  }
  return out;
}

std::uint32_t peak_gather_index(std::uint32_t v, std::uint32_t size) {
  v ^= v >> 16;
  v *= 0x7feb352du;
  v ^= v >> 15;
  v *= 0x846ca68bu;
  v ^= v >> 16;
  return std::uint32_t((std::uint64_t(v) * size) >> 32);
}

std::vector<std::uint32_t> peak_gather(ocl::Device& dev, std::span<const std::uint32_t> table,
                                       std::size_t items, std::uint32_t lookups,
                                       std::uint32_t seed, std::size_t local) {
  check_range("gather table entries", table.size(), 1, 0xffffffffull);
  check_local(dev, local);
  check_items(items);
  ocl::Buffer<std::uint32_t> dt(dev, table, CL_MEM_READ_ONLY), out(dev, items);
  cl::Kernel k = dev.kernel(kProgram, "peak_gather");
  ocl::launch_local(dev, k, items, local, dt, cl_uint(table.size()), cl_uint(items),
                    cl_uint(lookups), cl_uint(seed), out);
  return out.read(dev);
}

std::vector<std::uint32_t> peak_gather_reference(std::span<const std::uint32_t> table,
                                                 std::size_t items, std::uint32_t lookups,
                                                 std::uint32_t seed) {
  check_range("gather table entries", table.size(), 1, 0xffffffffull);
  const auto size = std::uint32_t(table.size());
  std::vector<std::uint32_t> out(items);
  for (std::size_t i = 0; i < items; ++i) {
    const std::uint32_t key = std::uint32_t(i) * lookups + seed;
    std::uint32_t sum = 0;
    for (std::uint32_t k = 0; k < lookups; ++k) sum += table[peak_gather_index(key + k, size)];
    out[i] = sum;
  }
  return out;
}

}  // namespace binpick
