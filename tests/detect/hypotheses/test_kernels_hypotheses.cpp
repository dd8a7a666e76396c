// The three kernels of a highest-point round (kernels/hypotheses.cl), each launched by
// itself on random input and compared with a plain C++ reference of that one step
// (tests/support/kernel_refs.hpp): chunk argmin and exclusion exactly (comparisons only, and
// bp_dist2 on both sides), the selected hypothesis' pixel, u, v, depth and z exactly and its x, y
// within 4 ulp (a float division and a product; OpenCL allows its division 2.5 ulp). The
// composed rounds are tests/detect/hypotheses/test_hypotheses.cpp's.
#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <string>
#include <tuple>

#include "host/detect/hypotheses/hypotheses.hpp"
#include "host/detect/scene/scene_chunks.hpp"
#include "host/detect/scene/scene_lowpass.hpp"
#include "tests/support/hypothesis_checks.hpp"
#include "tests/support/kernel_refs.hpp"

using namespace binpick;
using namespace binpick::test;

namespace {

constexpr u32 kCanary = 0xdeadbeefu;
constexpr std::size_t kGuard = 8;

const bp_hypothesis kCanaryHypothesis{kCanary, kCanary, kCanary, -1.0f, -1.0f, -1.0f, -1.0f, {kCanary, kCanary}};

}  // namespace

TEST(HypothesisKernels, hyp_chunk_argmin_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("hypotheses.cl", "hyp_chunk_argmin");
  std::mt19937 rng(601);
  for (auto [w, h, holes, excluded_p] : {std::tuple{1u, 1u, 0.0f, 0.0}, {37u, 23u, 0.1f, 0.3},
                                         {160u, 120u, 0.05f, 0.0}, {301u, 77u, 0.5f, 0.9},
                                         {64u, 64u, 0.0f, 1.0}}) {
    const PointImage pts = random_point_image(rng, w, h, holes);
    const std::size_t n = std::size_t(w) * h;
    const std::vector<float> filtered = tied_filtered(pts, 2);
    const std::vector<std::uint8_t> excluded = random_flags(rng, n, excluded_p);
    ocl::Buffer<float> f_buf = upload(dev, filtered);
    ocl::Buffer<std::uint8_t> x_buf = upload(dev, excluded);
    for (const Chunks ch : {chunks_for(n), Chunks{u32(n), 1u}, Chunks{u32((n + 96) / 97), 97u}}) {
      ocl::Buffer<float> depth = guarded_buffer(dev, std::vector<float>(ch.count, -1.0f), kGuard, -1.0f);
      ocl::Buffer<u32> pixel = guarded_buffer(dev, std::vector<u32>(ch.count, kCanary), kGuard, kCanary);
      ocl::launch(dev, k, ch.count, f_buf, x_buf, u32(n), ch.size, depth, pixel);
      ChunkArgmin want = hyp_chunk_argmin_reference(filtered, excluded, ch.size, ch.count);
      want.depth.insert(want.depth.end(), kGuard, -1.0f);
      want.pixel.insert(want.pixel.end(), kGuard, kCanary);
      ASSERT_EQ(pixel.read(dev), want.pixel) << w << "x" << h << " chunk " << ch.size;
      ASSERT_EQ(depth.read(dev), want.depth) << w << "x" << h << " chunk " << ch.size;  // INFINITY where none
    }
  }
}

TEST(HypothesisKernels, hyp_select_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("hypotheses.cl", "hyp_select");
  std::mt19937 rng(602);
  for (auto [w, h, holes] : {std::tuple{1u, 1u, 0.0f}, {37u, 23u, 0.1f}, {160u, 120u, 0.05f},
                             {301u, 77u, 0.5f}}) {
    const PointImage pts = random_point_image(rng, w, h, holes);
    const std::size_t n = std::size_t(w) * h;
    const std::vector<float> filtered = tied_filtered(pts, 3);
    ocl::Buffer<float> p_buf = upload(dev, pts.xyzw), f_buf = upload(dev, filtered);
    for (int t = 0; t < 6; ++t) {
      // Random chunk results: valid pixels with their filtered depth (ties between chunks on
      // purpose), or no pixel; for t = 0 none at all.
      const u32 parts = t == 1 ? 1u : 1u + u32(rng() % 300);
      std::vector<float> part_depth(parts, INFINITY);
      std::vector<u32> part_pixel(parts, BP_NO_PIXEL);
      std::uniform_int_distribution<std::size_t> pick(0, n - 1);
      for (u32 g = 0; g < parts && t != 0; ++g) {
        const std::size_t i = pick(rng);
        if (filtered[i] > 0 && rng() % 4 != 0) part_depth[g] = filtered[i], part_pixel[g] = u32(i);
      }
      const u32 slot = u32(t);  // the round k: hyps[k], the others untouched
      std::vector<bp_hypothesis> hyps(8, kCanaryHypothesis);
      ocl::Buffer<bp_hypothesis> h_buf = upload(dev, hyps);
      ocl::Buffer<float> d_buf = upload(dev, part_depth);
      ocl::Buffer<u32> px_buf = upload(dev, part_pixel);
      // Only work item 0 acts: launched with 5 must give the same.
      ocl::launch(dev, k, t % 2 ? 5 : 1, d_buf, px_buf, parts, p_buf, f_buf, w, slot, h_buf);
      const std::vector<bp_hypothesis> got = h_buf.read(dev);
      const bp_hypothesis want = hyp_select_reference(part_depth, part_pixel, pts.xyzw, filtered, w);
      const std::string at = std::to_string(w) + "x" + std::to_string(h) + " t " + std::to_string(t);
      expect_same(got[slot], want, at);
      for (u32 j = 0; j < hyps.size(); ++j)
        if (j != slot) {
          EXPECT_EQ(got[j].pixel, kCanary) << at << " slot " << j;
        }
      if (t == 0) {
        EXPECT_EQ(want.pixel, BP_NO_PIXEL);
      }
    }
  }
}

TEST(HypothesisKernels, hyp_exclude_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("hypotheses.cl", "hyp_exclude");
  std::mt19937 rng(603);
  for (auto [w, h, holes] : {std::tuple{1u, 1u, 0.0f}, {37u, 23u, 0.1f}, {160u, 120u, 0.05f},
                             {301u, 77u, 0.5f}}) {
    const PointImage pts = random_point_image(rng, w, h, holes);
    const std::size_t n = std::size_t(w) * h;
    const std::vector<float> filtered = lowpass_depth_reference(pts, 2);
    ocl::Buffer<float> p_buf = upload(dev, pts.xyzw);
    std::uniform_int_distribution<std::size_t> pick(0, n - 1);
    for (int t = 0; t < 6; ++t) {
      // The hypothesis of a random valid pixel (as hyp_select makes it), or none (t = 0).
      bp_hypothesis hyp{BP_NO_PIXEL, 0, 0, 0.0f, 0.0f, 0.0f, 0.0f, {0, 0}};
      for (int tries = 0; tries < 100 && t != 0; ++tries) {
        const std::size_t i = pick(rng);
        if (filtered[i] > 0) {
          hyp = hyp_select_reference({filtered[i]}, {u32(i)}, pts.xyzw, filtered, w);
          break;
        }
      }
      // A radius of 0 (only the own pixel), then growing; exactly on the boundary for t = 5: the
      // distance of some pixel's point, which must be excluded ("<=").
      float radius2 = t <= 1 ? 0.0f : float(std::pow(15.0f * t, 2));
      if (t == 5 && hyp.pixel != BP_NO_PIXEL) {
        const float* q = &pts.xyzw[4 * pick(rng)];
        radius2 = bp_dist2(q[0], q[1], q[2], hyp.x, hyp.y, hyp.z);
      }
      std::vector<bp_hypothesis> hyps(4, kCanaryHypothesis);
      const u32 slot = u32(t % 4);
      hyps[slot] = hyp;
      ocl::Buffer<bp_hypothesis> h_buf = upload(dev, hyps);
      std::vector<std::uint8_t> excluded = random_flags(rng, n, 0.2);
      ocl::Buffer<std::uint8_t> x_buf = guarded_buffer(dev, excluded, kGuard, std::uint8_t(7));
      ocl::launch(dev, k, n, p_buf, u32(n), h_buf, slot, radius2, x_buf);
      const std::vector<std::uint8_t> before = excluded;
      hyp_exclude_reference(pts.xyzw, hyp, radius2, excluded);
      excluded.insert(excluded.end(), kGuard, std::uint8_t(7));
      ASSERT_EQ(x_buf.read(dev), excluded) << w << "x" << h << " t " << t;
      if (hyp.pixel == BP_NO_PIXEL) {
        EXPECT_TRUE(std::equal(before.begin(), before.end(), excluded.begin()));
      } else {
        EXPECT_EQ(excluded[hyp.pixel], 1u);
      }
    }
  }
}

// The height keys (highest along the bin's up): random images with holes and random unit
// directions, among them straight down (keys = filtered depth exactly), one lying in the image
// plane and one pointing away from the camera (every key at or below 0: the least positive
// float). Within 4 ulp of the reference's magnitude (a float division, OpenCL allows 2.5 ulp);
// no data exactly 0.
TEST(HypothesisKernels, hyp_height_key_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("hypotheses.cl", "hyp_height_key");
  std::mt19937 rng(605);
  std::normal_distribution<float> N(0.0f, 1.0f);
  std::vector<Eigen::Vector3f> ups{{0, 0, -1}, {1, 0, 0}, {0, 0, 1}};
  for (int t = 0; t < 5; ++t) ups.push_back(Eigen::Vector3f(N(rng), N(rng), N(rng) - 2.0f).normalized());
  for (auto [w, h, holes] : {std::tuple{1u, 1u, 0.0f}, {37u, 23u, 0.1f}, {160u, 120u, 0.3f}}) {
    const PointImage pts = random_point_image(rng, w, h, holes);
    const std::size_t n = std::size_t(w) * h;
    const std::vector<float> filtered = lowpass_depth_reference(pts, 2);
    ocl::Buffer<float> p_buf = upload(dev, pts.xyzw), f_buf = upload(dev, filtered);
    for (std::size_t j = 0; j < ups.size(); ++j) {
      const Eigen::Vector3f& up = ups[j];
      ocl::Buffer<float> key = guarded_buffer(dev, std::vector<float>(n, -1.0f), kGuard, -1.0f);
      ocl::launch(dev, k, n, p_buf, f_buf, u32(n), up.x(), up.y(), up.z(), key);
      const std::vector<float> got = key.read(dev);
      const std::vector<float> want = height_keys_reference(pts, filtered, up);
      const std::string at = std::to_string(w) + "x" + std::to_string(h) + " up " + std::to_string(j);
      for (std::size_t i = 0; i < n; ++i) {
        if (!(filtered[i] > 0)) {
          ASSERT_EQ(got[i], 0.0f) << at << " pixel " << i;
          continue;
        }
        ASSERT_GT(got[i], 0.0f) << at << " pixel " << i;  // a valid pixel keeps a positive key
        ASSERT_NEAR(got[i], want[i], 4 * std::numeric_limits<float>::epsilon() * filtered[i])
            << at << " pixel " << i;
        if (j == 0) {
          ASSERT_EQ(got[i], filtered[i]) << at;  // straight down: the depth itself
        } else if (j == 2) {
          ASSERT_EQ(got[i], std::numeric_limits<float>::min()) << at;
        }
      }
      for (std::size_t i = n; i < got.size(); ++i) ASSERT_EQ(got[i], -1.0f) << at;
    }
  }
}

// Rounds of the routine (host/detect/hypotheses/hypotheses.cpp) step by step, each step checked on the
// previous step's device output, on images with ties, holes, and all pixels invalid; padded
// work groups of 16 for the argmin and exclusion (the extra work items must write nothing).
// The hypotheses found are find_hypotheses_reference's.
TEST(HypothesisKernels, RoundsStepByStepAndDegenerateImages) {
  auto& dev = ocl::Device::shared();
  cl::Kernel argmin = dev.kernel("hypotheses.cl", "hyp_chunk_argmin");
  cl::Kernel select = dev.kernel("hypotheses.cl", "hyp_select");
  cl::Kernel exclude = dev.kernel("hypotheses.cl", "hyp_exclude");
  std::mt19937 rng(604);
  std::vector<PointImage> images;
  images.push_back(PointImage{9, 5, std::vector<float>(4 * 45, 0.0f)});  // all invalid
  images.push_back(random_point_image(rng, 1, 1, 0.0f));
  images.push_back(random_point_image(rng, 61, 29, 0.2f));
  images.push_back(random_point_image(rng, 200, 150, 0.05f));
  for (std::size_t im = 0; im < images.size(); ++im) {
    const PointImage& pts = images[im];
    const std::size_t n = std::size_t(pts.width) * pts.height;
    const std::vector<float> filtered = tied_filtered(pts, 2);
    const HypothesisOptions opt{6, 40.0f};
    const float radius2 = opt.exclusion_radius * opt.exclusion_radius;
    const Chunks ch = chunks_for(n);
    ocl::Buffer<float> p_buf = upload(dev, pts.xyzw), f_buf = upload(dev, filtered);
    std::vector<std::uint8_t> excluded(n, 0);
    ocl::Buffer<std::uint8_t> x_buf = guarded_buffer(dev, excluded, kGuard, std::uint8_t(7));
    ocl::Buffer<float> part_depth = guarded_buffer(dev, std::vector<float>(ch.count, -1.0f), kGuard, -1.0f);
    ocl::Buffer<u32> part_pixel = guarded_buffer(dev, std::vector<u32>(ch.count, kCanary), kGuard, kCanary);
    ocl::Buffer<bp_hypothesis> hyps(dev, opt.count);
    std::vector<bp_hypothesis> found;
    for (u32 round = 0; round < opt.count; ++round) {
      const std::string at = "image " + std::to_string(im) + " round " + std::to_string(round);
      ocl::launch_local(dev, argmin, ch.count, 16, f_buf, x_buf, u32(n), ch.size, part_depth, part_pixel);
      ChunkArgmin want = hyp_chunk_argmin_reference(filtered, excluded, ch.size, ch.count);
      const std::vector<float> got_depth = part_depth.read(dev);
      const std::vector<u32> got_pixel = part_pixel.read(dev);
      ASSERT_EQ(std::vector<u32>(got_pixel.begin(), got_pixel.begin() + ch.count), want.pixel) << at;
      ASSERT_EQ(std::vector<float>(got_depth.begin(), got_depth.begin() + ch.count), want.depth) << at;
      for (std::size_t g = ch.count; g < got_pixel.size(); ++g) {
        ASSERT_EQ(got_pixel[g], kCanary) << at;
        ASSERT_EQ(got_depth[g], -1.0f) << at;
      }
      ocl::launch(dev, select, 1, part_depth, part_pixel, ch.count, p_buf, f_buf, pts.width, round, hyps);
      const bp_hypothesis want_h = hyp_select_reference(want.depth, want.pixel, pts.xyzw, filtered, pts.width);
      const bp_hypothesis got_h = hyps.read(dev)[round];
      expect_same(got_h, want_h, at);
      found.push_back(got_h);
      ocl::launch_local(dev, exclude, n, 16, p_buf, u32(n), hyps, round, radius2, x_buf);
      hyp_exclude_reference(pts.xyzw, got_h, radius2, excluded);
      const std::vector<std::uint8_t> got_x = x_buf.read(dev);
      ASSERT_TRUE(std::equal(excluded.begin(), excluded.end(), got_x.begin())) << at;
      for (std::size_t i = n; i < got_x.size(); ++i) ASSERT_EQ(got_x[i], 7u) << at;
    }
    const std::vector<Hypothesis> want = find_hypotheses_reference(pts, filtered, opt);
    std::size_t valid = 0;
    while (valid < found.size() && found[valid].pixel != BP_NO_PIXEL) ++valid;
    ASSERT_EQ(valid, want.size()) << im;
    for (std::size_t j = 0; j < valid; ++j) EXPECT_EQ(found[j].pixel, want[j].pixel) << im << " " << j;
    for (std::size_t j = valid; j < found.size(); ++j) EXPECT_EQ(found[j].pixel, BP_NO_PIXEL);
    if (im == 0) {
      EXPECT_EQ(valid, 0u);
    }
    if (im == 1) {
      EXPECT_EQ(valid, 1u);
    }
  }
}
