// The three kernels of the device prefix sum (kernels/device_scan.cl), each launched by itself on
// random input and compared with a plain C++ reference of that one step
// (tests/support/kernel_refs.hpp): all integer, so exactly. The composed scan is
// tests/train/test_voxel_subsample.cpp's DeviceScan test.
#include <gtest/gtest.h>

#include <random>
#include <tuple>

#include "host/train/device_scan.hpp"
#include "tests/support/kernel_refs.hpp"

using namespace binpick;
using namespace binpick::test;

namespace {

constexpr u32 kCanary = 0xdeadbeefu;
constexpr std::size_t kGuard = 8;

std::vector<u32> random_values(std::mt19937& rng, std::size_t n, u32 max) {
  std::uniform_int_distribution<u32> v(0, max);
  std::vector<u32> out(n);
  for (auto& x : out) x = v(rng);
  return out;
}

// The routine's split (host/train/device_scan.cpp).
std::pair<u32, u32> routine_blocks(std::size_t n) {
  const std::size_t blocks = std::clamp<std::size_t>(n / 4096, 1, 256);
  return {u32(blocks), u32((n + blocks - 1) / blocks)};
}

struct Case {
  std::size_t n;
  u32 blocks, chunk;
};

// The routine's splits, and others the kernels allow: one chunk, chunks of 1, and more chunks
// than values need (trailing chunks that start at or after n).
std::vector<Case> cases() {
  std::vector<Case> out;
  for (std::size_t n : {1u, 2u, 7u, 4095u, 4096u, 4097u, 100003u}) {
    const auto [b, c] = routine_blocks(n);
    out.push_back({n, b, c});
  }
  out.push_back({1000, 1, 1000});
  out.push_back({37, 37, 1});
  out.push_back({10, 7, 2});    // chunks 5 and 6 start past n
  out.push_back({5, 4, 2});     // chunk 3 starts past n
  out.push_back({999, 256, 4}); // 6 empty chunks at the end
  return out;
}

}  // namespace

TEST(ScanKernels, scan_chunks_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("device_scan.cl", "scan_chunks");
  std::mt19937 rng(101);
  for (const Case& c : cases()) {
    for (u32 max : {0u, 1u, 1000u}) {  // all zero, 0/1 flags (compaction), counts
      const std::vector<u32> in = random_values(rng, c.n, max);
      ocl::Buffer<u32> in_buf = upload(dev, in);
      ocl::Buffer<u32> out = guarded_buffer(dev, std::vector<u32>(c.n + 1, kCanary), kGuard, kCanary);
      ocl::Buffer<u32> sums = guarded_buffer(dev, std::vector<u32>(c.blocks + 1, kCanary), kGuard, kCanary);
      ocl::launch_tasks(dev, k, c.blocks, in_buf, u32(c.n), c.chunk, out, sums);
      const ScanChunksResult want = scan_chunks_reference(in, c.chunk, c.blocks);
      const std::vector<u32> got_out = out.read(dev), got_sums = sums.read(dev);
      const std::string at = "n " + std::to_string(c.n) + " blocks " + std::to_string(c.blocks) +
                             " chunk " + std::to_string(c.chunk) + " max " + std::to_string(max);
      ASSERT_EQ(std::vector<u32>(got_out.begin(), got_out.begin() + c.n), want.out) << at;
      ASSERT_EQ(std::vector<u32>(got_sums.begin(), got_sums.begin() + c.blocks), want.sums) << at;
      // out[n] (the total, written by the next kernel) and everything past are untouched.
      for (std::size_t i = c.n; i < got_out.size(); ++i) ASSERT_EQ(got_out[i], kCanary) << at << " " << i;
      for (std::size_t i = c.blocks; i < got_sums.size(); ++i) ASSERT_EQ(got_sums[i], kCanary) << at << " " << i;
    }
  }
}

TEST(ScanKernels, scan_chunk_sums_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("device_scan.cl", "scan_chunk_sums");
  std::mt19937 rng(102);
  for (auto [blocks, n, global] : {std::tuple{1u, 1u, 1u}, {2u, 5u, 1u}, {7u, 100u, 1u},
                                   {256u, 100003u, 1u}, {256u, 4096u, 33u}, {1u, 0u, 5u}}) {
    // Only work item 0 acts: a launch of `global` > 1 items must give the same.
    std::vector<u32> sums = random_values(rng, blocks + 1, 100000);
    sums[blocks] = kCanary;  // overwritten with the total
    std::vector<u32> out = random_values(rng, n + 1, 1000);
    ocl::Buffer<u32> sums_buf = guarded_buffer(dev, sums, kGuard, kCanary);
    ocl::Buffer<u32> out_buf = guarded_buffer(dev, out, kGuard, kCanary);
    ocl::launch(dev, k, global, sums_buf, blocks, out_buf, n);
    scan_chunk_sums_reference(sums, blocks, out, n);
    sums.insert(sums.end(), kGuard, kCanary);
    out.insert(out.end(), kGuard, kCanary);
    EXPECT_EQ(sums_buf.read(dev), sums) << blocks << " " << n;
    EXPECT_EQ(out_buf.read(dev), out) << blocks << " " << n;  // only out[n] changes
  }
}

TEST(ScanKernels, scan_add_offsets_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("device_scan.cl", "scan_add_offsets");
  std::mt19937 rng(103);
  for (const Case& c : cases()) {
    std::vector<u32> out = random_values(rng, c.n + 1, 1u << 20);
    std::vector<u32> sums = random_values(rng, c.blocks + 1, 1u << 30);
    ocl::Buffer<u32> out_buf = guarded_buffer(dev, out, kGuard, kCanary);
    ocl::Buffer<u32> sums_buf = upload(dev, sums);
    ocl::launch(dev, k, c.n, out_buf, u32(c.n), c.chunk, sums_buf);
    scan_add_offsets_reference(out, u32(c.n), c.chunk, sums);  // out[n] keeps its value
    out.insert(out.end(), kGuard, kCanary);
    ASSERT_EQ(out_buf.read(dev), out) << c.n << " " << c.chunk;
  }
}

// The kernels guard their tails: launched in work groups that do not divide the work (as a
// device may round a global size up), the extra work items change nothing.
TEST(ScanKernels, TailsOfPaddedWorkGroupsChangeNothing) {
  auto& dev = ocl::Device::shared();
  cl::Kernel add = dev.kernel("device_scan.cl", "scan_add_offsets");
  std::mt19937 rng(104);
  for (std::size_t n : {1u, 31u, 33u, 1000u}) {
    const u32 chunk = 7, blocks = u32((n + chunk - 1) / chunk);
    std::vector<u32> out = random_values(rng, n + 1, 1000), sums = random_values(rng, blocks + 1, 1000);
    ocl::Buffer<u32> out_buf = guarded_buffer(dev, out, kGuard, kCanary);
    ocl::Buffer<u32> sums_buf = upload(dev, sums);
    ocl::launch_local(dev, add, n, 32, out_buf, u32(n), chunk, sums_buf);
    scan_add_offsets_reference(out, u32(n), chunk, sums);
    out.insert(out.end(), kGuard, kCanary);
    EXPECT_EQ(out_buf.read(dev), out) << n;
  }
}

// The routine's sequence step by step with other splits than the routine's own (including empty
// trailing chunks): each step's output checked, and the composition is the exclusive scan.
TEST(ScanKernels, SequenceOfTheThreeStepsIsTheExclusiveScan) {
  auto& dev = ocl::Device::shared();
  cl::Kernel chunks = dev.kernel("device_scan.cl", "scan_chunks");
  cl::Kernel totals = dev.kernel("device_scan.cl", "scan_chunk_sums");
  cl::Kernel add = dev.kernel("device_scan.cl", "scan_add_offsets");
  std::mt19937 rng(105);
  for (const Case& c : cases()) {
    const std::vector<u32> in = random_values(rng, c.n, 3);
    ocl::Buffer<u32> in_buf = upload(dev, in), out(dev, c.n + 1), sums(dev, c.blocks + 1);
    ocl::launch_tasks(dev, chunks, c.blocks, in_buf, u32(c.n), c.chunk, out, sums);
    ScanChunksResult want = scan_chunks_reference(in, c.chunk, c.blocks);
    ASSERT_EQ(sums.read(dev, c.blocks), want.sums);
    ASSERT_EQ(out.read(dev, c.n), want.out);
    ocl::launch(dev, totals, 1, sums, c.blocks, out, u32(c.n));
    want.sums.push_back(0);
    want.out.push_back(0);
    scan_chunk_sums_reference(want.sums, c.blocks, want.out, u32(c.n));
    ASSERT_EQ(sums.read(dev), want.sums);
    ocl::launch(dev, add, c.n, out, u32(c.n), c.chunk, sums);
    scan_add_offsets_reference(want.out, u32(c.n), c.chunk, want.sums);
    ASSERT_EQ(out.read(dev), want.out);
    EXPECT_EQ(want.out, exclusive_scan_reference(in)) << c.n << " " << c.blocks;
  }
}
