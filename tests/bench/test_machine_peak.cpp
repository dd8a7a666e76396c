// The machine-peak kernels (kernels/machine_peak.cl) against their C++ references on random
// input, their degenerate launches, the option checks, and one quick measurement (finite and
// positive figures only: no timing assertions, the machine may be busy).
//
// Tolerances: integer results exactly. Float results within 4 ulps (EXPECT_FLOAT_EQ): both
// sides use one correctly rounded fma per step and add in the same order with contraction off,
// so they normally agree bit for bit; the margin only covers a compiler reassociating the
// final lane sums.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "bench/lib/machine_peak.hpp"
#include "host/core/error.hpp"

using namespace binpick;

namespace {

ocl::Device& dev() { return ocl::Device::shared(); }

std::vector<float> random_floats(std::mt19937& rng, std::size_t n, float lo, float hi) {
  std::uniform_real_distribution<float> u(lo, hi);
  std::vector<float> v(n);
  for (float& x : v) x = u(rng);
  return v;
}

void expect_floats_eq(const std::vector<float>& got, const std::vector<float>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_FLOAT_EQ(got[i], want[i]) << "at " << i;
}

}  // namespace

TEST(MachinePeakKernels, peak_stream_triad_matches_reference) {
  std::mt19937 rng(1);
  for (const std::size_t float4s : {std::size_t(1), std::size_t(65), std::size_t(4099)}) {
    const auto b = random_floats(rng, 4 * float4s, -1e3f, 1e3f);
    const auto c = random_floats(rng, 4 * float4s, -1e3f, 1e3f);
    const float s = std::uniform_real_distribution<float>(-10.0f, 10.0f)(rng);
    expect_floats_eq(peak_stream_triad(dev(), b, c, s), peak_stream_triad_reference(b, c, s));
  }
}

TEST(MachinePeakKernels, peak_stream_triad_degenerate_sizes_and_work_groups) {
  std::mt19937 rng(2);
  const auto b = random_floats(rng, 4 * 67, -1.0f, 1.0f), c = random_floats(rng, 4 * 67, -1.0f, 1.0f);
  for (const std::size_t local : {std::size_t(1), std::size_t(7), std::size_t(256)})
    expect_floats_eq(peak_stream_triad(dev(), b, c, 0.5f, local),
                     peak_stream_triad_reference(b, c, 0.5f));
  EXPECT_TRUE(peak_stream_triad(dev(), {}, {}, 2.0f).empty());
  // a = b + 0 c = b exactly
  expect_floats_eq(peak_stream_triad(dev(), b, c, 0.0f), b);
}

TEST(MachinePeakKernels, peak_fma_matches_reference) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 3; ++trial) {
    const std::size_t items = std::uniform_int_distribution<std::size_t>(1, 700)(rng);
    const auto iterations = std::uniform_int_distribution<std::uint32_t>(1, 300)(rng);
    const float mul = std::uniform_real_distribution<float>(0.5f, 0.999f)(rng);
    const float add = std::uniform_real_distribution<float>(-1.0f, 1.0f)(rng);
    SCOPED_TRACE(testing::Message() << items << " items, " << iterations << " steps, mul " << mul
                                    << ", add " << add);
    expect_floats_eq(peak_fma(dev(), items, iterations, mul, add),
                     peak_fma_reference(items, iterations, mul, add));
  }
}

TEST(MachinePeakKernels, peak_fma_degenerate_inputs) {
  // Zero steps: the start values, sum over 128 lanes of x + lane = 128 x + 8128,
  // x = (i mod 1024) / 1024.
  const std::size_t items = 1500;  // wraps the i mod 1024; not a multiple of the work group
  const auto start = peak_fma(dev(), items, 0, 0.9f, 0.1f);
  ASSERT_EQ(start.size(), items);
  for (std::size_t i = 0; i < items; ++i)
    ASSERT_EQ(start[i], 128.0f * float(i % 1024) / 1024.0f + 8128.0f) << "at " << i;
  expect_floats_eq(start, peak_fma_reference(items, 0, 0.9f, 0.1f));
  // x -> x / 2 + 1/2 reaches its fixed point 1 exactly: 128 lanes of 1.
  for (float v : peak_fma(dev(), 3, 200, 0.5f, 0.5f, 1)) EXPECT_EQ(v, 128.0f);
  expect_floats_eq(peak_fma(dev(), 1, 17, 0.75f, -0.25f), peak_fma_reference(1, 17, 0.75f, -0.25f));
  EXPECT_TRUE(peak_fma(dev(), 0, 10, 0.5f, 0.5f).empty());
}

TEST(MachinePeakKernels, peak_int_ops_matches_reference) {
  std::mt19937 rng(4);
  std::uniform_int_distribution<std::uint32_t> any;
  for (int trial = 0; trial < 3; ++trial) {
    const std::size_t items = std::uniform_int_distribution<std::size_t>(1, 900)(rng);
    const auto iterations = std::uniform_int_distribution<std::uint32_t>(1, 500)(rng);
    const std::uint32_t x = any(rng), y = any(rng);
    SCOPED_TRACE(testing::Message() << items << " items, " << iterations << " steps");
    EXPECT_EQ(peak_int_ops(dev(), items, iterations, x, y),
              peak_int_ops_reference(items, iterations, x, y));
  }
}

TEST(MachinePeakKernels, peak_int_ops_degenerate_inputs) {
  // Zero steps: sum of 128 i + lane over 128 lanes = 16384 i + 8128 (mod 2^32).
  const auto start = peak_int_ops(dev(), 100, 0, 1u, 2u, 7);
  ASSERT_EQ(start.size(), 100u);
  for (std::uint32_t i = 0; i < 100; ++i) EXPECT_EQ(start[i], 16384u * i + 8128u);
  // x = y = 0: nothing changes whatever the steps.
  EXPECT_EQ(peak_int_ops(dev(), 1, 1000, 0u, 0u), std::vector<std::uint32_t>{8128u});
  EXPECT_EQ(peak_int_ops(dev(), 1, 3, 0xdeadbeefu, 12345u),
            peak_int_ops_reference(1, 3, 0xdeadbeefu, 12345u));
  EXPECT_TRUE(peak_int_ops(dev(), 0, 3, 1u, 1u).empty());
}

TEST(MachinePeakKernels, peak_gather_matches_reference) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<std::uint32_t> any;
  for (const std::size_t size : {std::size_t(1000), std::size_t(1) << 16, std::size_t(123457)}) {
    std::vector<std::uint32_t> table(size);
    for (auto& v : table) v = any(rng);
    const std::size_t items = std::uniform_int_distribution<std::size_t>(1, 2000)(rng);
    const auto lookups = std::uniform_int_distribution<std::uint32_t>(1, 100)(rng);
    const std::uint32_t seed = any(rng);
    SCOPED_TRACE(testing::Message() << size << " entries, " << items << " items, " << lookups
                                    << " lookups");
    EXPECT_EQ(peak_gather(dev(), table, items, lookups, seed),
              peak_gather_reference(table, items, lookups, seed));
  }
}

TEST(MachinePeakKernels, peak_gather_degenerate_inputs) {
  const std::vector<std::uint32_t> one{7u};
  EXPECT_EQ(peak_gather(dev(), one, 3, 5, 0, 1), (std::vector<std::uint32_t>{35u, 35u, 35u}));
  EXPECT_EQ(peak_gather(dev(), one, 2, 0, 9), (std::vector<std::uint32_t>{0u, 0u}));
  EXPECT_TRUE(peak_gather(dev(), one, 0, 4, 0).empty());
  const std::vector<std::uint32_t> table{1u, 10u, 100u};
  EXPECT_EQ(peak_gather(dev(), table, 1, 50, 42), peak_gather_reference(table, 1, 50, 42));
}

// The hash spreads consecutive keys over the whole table (the kernel's premise: random slots).
TEST(MachinePeakKernels, peak_gather_index_covers_the_table) {
  const std::uint32_t size = 1000;
  std::vector<int> hits(size, 0);
  for (std::uint32_t k = 0; k < 100000; ++k) {
    const std::uint32_t idx = peak_gather_index(k, size);
    ASSERT_LT(idx, size);
    ++hits[idx];
  }
  // 100 expected per slot; a uniform spread keeps every slot within a few sigma (10).
  for (int h : hits) {
    EXPECT_GT(h, 40);
    EXPECT_LT(h, 160);
  }
}

TEST(MachinePeak, bad_options_are_rejected) {
  auto rejects = [](auto change) {
    PeakOptions o;
    change(o);
    EXPECT_THROW(check_peak_options(dev(), o), InputError);
    EXPECT_THROW(measure_machine_peak(dev(), o), InputError);
  };
  EXPECT_NO_THROW(check_peak_options(dev(), PeakOptions{}));
  rejects([](PeakOptions& o) { o.repetitions = 0; });
  rejects([](PeakOptions& o) { o.repetitions = -3; });
  rejects([](PeakOptions& o) { o.local_size = 0; });
  rejects([](PeakOptions& o) { o.local_size = std::size_t(1) << 30; });
  rejects([](PeakOptions& o) { o.stream_bytes = 0; });
  rejects([](PeakOptions& o) { o.stream_bytes = std::size_t(1) << 50; });
  rejects([](PeakOptions& o) { o.gather_table_bytes = 3; });
  rejects([](PeakOptions& o) { o.gather_cached_table_bytes = std::size_t(1) << 50; });
  rejects([](PeakOptions& o) { o.fma_items = 0; });
  rejects([](PeakOptions& o) { o.fma_iterations = 0; });
  rejects([](PeakOptions& o) { o.fma_items = 1 << 20, o.fma_iterations = 1 << 20; });  // 2^40 steps
  rejects([](PeakOptions& o) { o.int_iterations = 0; });
  rejects([](PeakOptions& o) { o.gather_items = std::size_t(1) << 40; });
  rejects([](PeakOptions& o) { o.gather_lookups = 0; });
}

TEST(MachinePeakKernels, bad_inputs_are_rejected) {
  const std::vector<float> four(4, 1.0f), five(5, 1.0f), eight(8, 1.0f);
  EXPECT_THROW(peak_stream_triad(dev(), four, eight, 1.0f), InputError);
  EXPECT_THROW(peak_stream_triad(dev(), five, five, 1.0f), InputError);
  EXPECT_THROW(peak_stream_triad_reference(five, five, 1.0f), InputError);
  EXPECT_THROW(peak_stream_triad(dev(), four, four, 1.0f, 0), InputError);
  EXPECT_THROW(peak_fma(dev(), 4, 1, 0.5f, 0.5f, 0), InputError);
  EXPECT_THROW(peak_int_ops(dev(), 4, 1, 1u, 1u, std::size_t(1) << 30), InputError);
  EXPECT_THROW(peak_gather(dev(), {}, 4, 1, 0), InputError);
  EXPECT_THROW(peak_gather_reference({}, 4, 1, 0), InputError);
}

TEST(MachinePeak, quick_measurement_gives_finite_positive_figures) {
  PeakOptions o;
  o.quick = true;
  const MachinePeak p = measure_machine_peak(dev(), o);
  for (double v : {p.stream_gb_s, p.fma_gflop_s, p.int_gop_s, p.gather_glookup_s,
                   p.gather_cached_glookup_s, p.seconds}) {
    EXPECT_TRUE(std::isfinite(v));
    EXPECT_GT(v, 0.0);
  }
  EXPECT_FALSE(p.device.empty());
  EXPECT_GE(p.compute_units, 1u);
  EXPECT_TRUE(p.used.quick);
  EXPECT_EQ(p.used.stream_bytes, PeakOptions{}.stream_bytes / 16);
  EXPECT_LE(p.used.repetitions, 2);
  EXPECT_NE(describe(p).find("quick"), std::string::npos);
}
