// The highest-point rounds on a depth image's points (find_hypotheses with its camera): the tile
// kernels of kernels/hypotheses.cl (hyp_tile_argmin, hyp_select on tiles, hyp_exclude_rect) each
// against a plain C++ reference on random input, exactly (comparisons only; the selected
// point's x, y within 4 ulp as in test_kernels_hypotheses.cpp), and the routine with a camera
// against the routine without one and find_hypotheses_reference: the same pixels, round by round.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <tuple>

#include "host/core/error.hpp"
#include "host/detect/hypotheses/hypotheses.hpp"
#include "host/detect/scene/scene_lowpass.hpp"
#include "host/detect/scene/scene_prepare.hpp"
#include "tests/support/hypothesis_checks.hpp"
#include "tests/support/kernel_refs.hpp"
#include "tests/support/test_device.hpp"

using namespace binpick;
using namespace binpick::test;

namespace {

constexpr u32 kCanary = 0xdeadbeefu;
constexpr std::size_t kGuard = 8;

// hyp_tile_argmin: for the tiles (tx0 .. tx0 + ntx - 1, ty0 .. ty0 + nty - 1) the valid (> 0),
// not excluded pixel of smallest filtered depth, the smallest index among equals, at entry
// ty * tiles_x + tx; the other entries as they were.
void tile_argmin_reference(const std::vector<float>& filtered,
                           const std::vector<std::uint8_t>& excluded, u32 width, u32 height,
                           const Tiles& t, u32 tx0, u32 ty0, u32 ntx, u32 nty,
                           std::vector<float>& depth, std::vector<u32>& pixel) {
  for (u32 ty = ty0; ty < ty0 + nty; ++ty)
    for (u32 tx = tx0; tx < tx0 + ntx; ++tx) {
      float best = INFINITY;
      u32 best_i = BP_NO_PIXEL;
      for (u32 v = ty * t.h; v < std::min(height, (ty + 1) * t.h); ++v)
        for (u32 u = tx * t.w; u < std::min(width, (tx + 1) * t.w); ++u) {
          const u32 i = v * width + u;
          if (filtered[i] > 0.0f && !excluded[i] && (filtered[i] < best || (filtered[i] == best && i < best_i)))
            best = filtered[i], best_i = i;
        }
      depth[ty * t.x + tx] = best;
      pixel[ty * t.x + tx] = best_i;
    }
}

// hyp_exclude_rect: hyp_exclude on the rectangle [u0, u1) x [v0, v1) only.
void exclude_rect_reference(const std::vector<float>& points, u32 width, u32 u0, u32 v0, u32 u1,
                            u32 v1, const bp_hypothesis& h, float radius2,
                            std::vector<std::uint8_t>& excluded) {
  if (h.pixel == BP_NO_PIXEL) return;
  for (u32 v = v0; v < v1; ++v)
    for (u32 u = u0; u < u1; ++u) {
      const u32 i = v * width + u;
      const float* p = &points[4 * std::size_t(i)];
      if (i == h.pixel || (p[3] != 0.0f && bp_dist2(p[0], p[1], p[2], h.x, h.y, h.z) <= radius2))
        excluded[i] = 1;
    }
}

bp_camera camera(u32 w, u32 h, float f, float cx_shift = 0.0f) {
  return {f, 1.1f * f, (w - 1) / 2.0f + cx_shift, (h - 1) / 2.0f, 0.1f, w, h, 0};
}

// A floor at 1000 mm (depth quantised to the 0.1 mm of the raw image: ties) under random
// spheres, with holes.
DepthImage spheres_on_a_floor(std::mt19937& rng, const bp_camera& cam, int spheres) {
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  struct Sphere { Eigen::Vector3f c; float r; };
  std::vector<Sphere> s;
  for (int k = 0; k < spheres; ++k) {
    const float z = 700.0f + 250.0f * U(rng);
    s.push_back({{(U(rng) - 0.5f) * z * cam.width / cam.fx, (U(rng) - 0.5f) * z * cam.height / cam.fy, z},
                 10.0f + 50.0f * U(rng)});
  }
  DepthImage img{cam.width, cam.height, std::vector<std::uint16_t>(std::size_t(cam.width) * cam.height, 0)};
  for (u32 v = 0; v < cam.height; ++v)
    for (u32 u = 0; u < cam.width; ++u) {
      if (U(rng) < 0.03f) continue;
      const Eigen::Vector3f d((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0f);
      float t = 1000.0f;
      for (const Sphere& q : s) {
        const float a = d.squaredNorm(), b = d.dot(q.c), c = q.c.squaredNorm() - q.r * q.r;
        if (b * b - a * c >= 0) t = std::min(t, (b - std::sqrt(b * b - a * c)) / a);
      }
      img.raw[std::size_t(v) * cam.width + u] = std::uint16_t(std::lround(t / cam.depth_scale));
    }
  return img;
}

}  // namespace

TEST(HypothesisTiles, TilesCoverTheImage) {
  for (auto [w, h] : {std::pair{1u, 1u}, {32u, 32u}, {33u, 31u}, {1600u, 900u}}) {
    const Tiles t = tiles_for(w, h);
    EXPECT_GE(t.x * t.w, w);
    EXPECT_LT((t.x - 1) * t.w, w);
    EXPECT_GE(t.y * t.h, h);
    EXPECT_LT((t.y - 1) * t.h, h);
  }
}

TEST(HypothesisTiles, hyp_tile_argmin_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("hypotheses.cl", "hyp_tile_argmin");
  std::mt19937 rng(611);
  for (auto [w, h, holes, excluded_p] : {std::tuple{1u, 1u, 0.0f, 0.0}, {37u, 23u, 0.1f, 0.3},
                                         {160u, 120u, 0.05f, 0.0}, {301u, 77u, 0.5f, 0.9},
                                         {64u, 64u, 0.0f, 1.0}}) {
    const PointImage pts = random_point_image(rng, w, h, holes);
    const std::size_t n = std::size_t(w) * h;
    const std::vector<float> filtered = tied_filtered(pts, 2);
    const std::vector<std::uint8_t> excluded = random_flags(rng, n, excluded_p);
    ocl::Buffer<float> f_buf = upload(dev, filtered);
    ocl::Buffer<std::uint8_t> x_buf = upload(dev, excluded);
    for (Tiles t : {tiles_for(w, h), Tiles{1, 1}, Tiles{7, 3}, Tiles{w, 1}}) {
      t.x = (w + t.w - 1) / t.w, t.y = (h + t.h - 1) / t.h;
      // All tiles, then a random block of them (the others keep their canaries).
      for (int block = 0; block < 2; ++block) {
        u32 tx0 = 0, ty0 = 0, ntx = t.x, nty = t.y;
        if (block) {
          tx0 = u32(rng() % t.x), ty0 = u32(rng() % t.y);
          ntx = 1 + u32(rng() % (t.x - tx0)), nty = 1 + u32(rng() % (t.y - ty0));
        }
        std::vector<float> want_depth(t.count(), -1.0f);
        std::vector<u32> want_pixel(t.count(), kCanary);
        ocl::Buffer<float> depth = guarded_buffer(dev, want_depth, kGuard, -1.0f);
        ocl::Buffer<u32> pixel = guarded_buffer(dev, want_pixel, kGuard, kCanary);
        ocl::launch(dev, k, std::size_t(ntx) * nty, f_buf, x_buf, w, h, t.w, t.h, t.x, tx0, ty0,
                    ntx, nty, depth, pixel);
        tile_argmin_reference(filtered, excluded, w, h, t, tx0, ty0, ntx, nty, want_depth, want_pixel);
        want_depth.insert(want_depth.end(), kGuard, -1.0f);
        want_pixel.insert(want_pixel.end(), kGuard, kCanary);
        const std::string at = std::to_string(w) + "x" + std::to_string(h) + " tile " +
                               std::to_string(t.w) + "x" + std::to_string(t.h) + " block " +
                               std::to_string(block);
        ASSERT_EQ(pixel.read(dev), want_pixel) << at;
        ASSERT_EQ(depth.read(dev), want_depth) << at;  // INFINITY where none
      }
    }
  }
}

TEST(HypothesisTiles, hyp_select_on_tiles_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("hypotheses.cl", "hyp_select");
  std::mt19937 rng(612);
  for (auto [w, h, holes] : {std::tuple{1u, 1u, 0.0f}, {37u, 23u, 0.1f}, {160u, 120u, 0.05f}}) {
    const PointImage pts = random_point_image(rng, w, h, holes);
    const std::size_t n = std::size_t(w) * h;
    const std::vector<float> filtered = tied_filtered(pts, 3);
    ocl::Buffer<float> p_buf = upload(dev, pts.xyzw), f_buf = upload(dev, filtered);
    for (int t = 0; t < 8; ++t) {
      // Random tile results in no pixel order, with ties between tiles on purpose (a few
      // distinct depths only); t = 0: none at all.
      const u32 parts = t == 1 ? 1u : 1u + u32(rng() % 300);
      std::vector<float> part_depth(parts, INFINITY);
      std::vector<u32> part_pixel(parts, BP_NO_PIXEL);
      std::uniform_int_distribution<std::size_t> pick(0, n - 1);
      std::vector<std::size_t> few;
      for (int j = 0; j < 3; ++j) few.push_back(pick(rng));
      for (u32 g = 0; g < parts && t != 0; ++g) {
        const std::size_t i = t % 2 ? pick(rng) : few[rng() % few.size()];
        if (filtered[i] > 0 && rng() % 4 != 0) {
          part_depth[g] = filtered[i];
          part_pixel[g] = u32(i);
        }
      }
      // Equal depths at different pixels: the smaller pixel must win whatever the order.
      if (t >= 2 && parts >= 2 && part_pixel[0] != BP_NO_PIXEL && n > 1) {
        const u32 other = part_pixel[0] > 0 ? part_pixel[0] - 1 : part_pixel[0] + 1;
        if (filtered[other] > 0) part_depth[1] = part_depth[0], part_pixel[1] = other;
      }
      const u32 slot = u32(t % 4);
      std::vector<bp_hypothesis> hyps(4, bp_hypothesis{kCanary, kCanary, kCanary, -1.0f, -1.0f, -1.0f, -1.0f, {kCanary, kCanary}});
      ocl::Buffer<bp_hypothesis> h_buf = upload(dev, hyps);
      ocl::Buffer<float> d_buf = upload(dev, part_depth);
      ocl::Buffer<u32> px_buf = upload(dev, part_pixel);
      ocl::launch(dev, k, t % 2 ? 5 : 1, d_buf, px_buf, parts, p_buf, f_buf, w, slot, h_buf);
      const std::vector<bp_hypothesis> got = h_buf.read(dev);
      const std::string at = std::to_string(w) + "x" + std::to_string(h) + " t " + std::to_string(t);
      expect_same(got[slot], hyp_select_reference(part_depth, part_pixel, pts.xyzw, filtered, w), at);
      for (u32 j = 0; j < hyps.size(); ++j)
        if (j != slot) {
          EXPECT_EQ(got[j].pixel, kCanary) << at << " slot " << j;
        }
      if (t == 0) {
        EXPECT_EQ(got[slot].pixel, BP_NO_PIXEL);
      }
    }
  }
}

TEST(HypothesisTiles, hyp_exclude_rect_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("hypotheses.cl", "hyp_exclude_rect");
  std::mt19937 rng(613);
  for (auto [w, h, holes] : {std::tuple{1u, 1u, 0.0f}, {37u, 23u, 0.1f}, {160u, 120u, 0.05f}}) {
    const PointImage pts = random_point_image(rng, w, h, holes);
    const std::size_t n = std::size_t(w) * h;
    const std::vector<float> filtered = lowpass_depth_reference(pts, 2);
    ocl::Buffer<float> p_buf = upload(dev, pts.xyzw);
    std::uniform_int_distribution<std::size_t> pick(0, n - 1);
    for (int t = 0; t < 6; ++t) {
      bp_hypothesis hyp{BP_NO_PIXEL, 0, 0, 0.0f, 0.0f, 0.0f, 0.0f, {0, 0}};
      for (int tries = 0; tries < 100 && t != 0; ++tries) {
        const std::size_t i = pick(rng);
        if (filtered[i] > 0) {
          hyp = hyp_select_reference({filtered[i]}, {u32(i)}, pts.xyzw, filtered, w);
          break;
        }
      }
      const float radius2 = t <= 1 ? 0.0f : float(std::pow(15.0f * t, 2));
      // The whole image for t = 2, else a random rectangle (holding the pixel or not).
      u32 u0 = 0, v0 = 0, u1 = w, v1 = h;
      if (t != 2) {
        u0 = u32(rng() % w), v0 = u32(rng() % h);
        u1 = u0 + 1 + u32(rng() % (w - u0)), v1 = v0 + 1 + u32(rng() % (h - v0));
      }
      std::vector<bp_hypothesis> hyps(3, hyp);
      ocl::Buffer<bp_hypothesis> h_buf = upload(dev, hyps);
      std::vector<std::uint8_t> excluded = random_flags(rng, n, 0.2);
      ocl::Buffer<std::uint8_t> x_buf = guarded_buffer(dev, excluded, kGuard, std::uint8_t(7));
      ocl::launch(dev, k, std::size_t(u1 - u0) * (v1 - v0), p_buf, w, u0, v0, u1 - u0, v1 - v0,
                  h_buf, u32(t % 3), radius2, x_buf);
      exclude_rect_reference(pts.xyzw, w, u0, v0, u1, v1, hyp, radius2, excluded);
      excluded.insert(excluded.end(), kGuard, std::uint8_t(7));
      ASSERT_EQ(x_buf.read(dev), excluded) << w << "x" << h << " t " << t;
    }
  }
}

// The routine with a camera picks what it picks without one and what the reference picks, on
// depth images of spheres on a floor (many equal depths), with and without a mask, with radii
// from 0 to one that reaches the camera (the whole image every round), off-centre principal
// points, and more rounds than the image has room for (the rounds run out early).
TEST(HypothesisTiles, RoutineWithACameraEqualsTheWholeImageRounds) {
  std::mt19937 rng(614);
  for (int t = 0; t < 8; ++t) {
    const bp_camera cam = camera(100 + 37 * t, 60 + 23 * t, 80.0f + 20.0f * t, t % 2 ? 17.5f : 0.0f);
    const DepthImage depth = spheres_on_a_floor(rng, cam, 2 + t);
    ScenePrepOptions po;
    po.normals_everywhere = false;
    po.lowpass_radius = t % 3;
    const PreparedScene s = prepare_scene(test_device(), depth, cam, po);
    const std::size_t n = std::size_t(cam.width) * cam.height;
    const std::vector<std::uint8_t> mask = random_flags(rng, n, 0.8);
    for (const float radius : {0.0f, 15.0f, 60.0f, 150.0f, 2000.0f}) {
      const HypothesisOptions opt{t == 7 ? 400u : 12u, radius};
      for (const auto* m : {static_cast<const std::vector<std::uint8_t>*>(nullptr), &mask}) {
        const std::string at = "t " + std::to_string(t) + " radius " + std::to_string(radius) +
                               (m ? " masked" : "");
        const auto got = find_hypotheses(test_device(), s.points, s.filtered_depth, opt, m, &cam);
        const auto whole = find_hypotheses(test_device(), s.points, s.filtered_depth, opt, m);
        const auto want = find_hypotheses_reference(s.points, s.filtered_depth, opt, m);
        ASSERT_EQ(got.size(), want.size()) << at;
        ASSERT_EQ(whole.size(), want.size()) << at;
        for (std::size_t k = 0; k < got.size(); ++k) {
          ASSERT_EQ(got[k].pixel, want[k].pixel) << at << " round " << k;
          ASSERT_EQ(got[k].pixel, whole[k].pixel) << at << " round " << k;
          EXPECT_EQ(got[k].depth, whole[k].depth) << at;
          EXPECT_EQ(got[k].point, whole[k].point) << at;
        }
        if (t == 7 && radius == 2000.0f) {
          EXPECT_EQ(got.size(), 1u) << at;  // the first round excludes every pixel
        }
      }
    }
  }
}

TEST(HypothesisTiles, DegenerateImagesAndAMismatchedCamera) {
  for (auto [w, h] : {std::pair{1u, 1u}, {40u, 30u}}) {
    const bp_camera cam = camera(w, h, 50.0f);
    DepthImage depth{w, h, std::vector<std::uint16_t>(std::size_t(w) * h, 0)};
    const HypothesisOptions opt{5, 20.0f};
    {
      const PreparedScene none = prepare_scene(test_device(), depth, cam);
      EXPECT_TRUE(find_hypotheses(test_device(), none.points, none.filtered_depth, opt, nullptr, &cam).empty());
    }
    depth.raw.back() = 4321;
    const PreparedScene one = prepare_scene(test_device(), depth, cam);
    const auto got = find_hypotheses(test_device(), one.points, one.filtered_depth, opt, nullptr, &cam);
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].pixel, w * h - 1);
    const bp_camera wider = camera(w + 1, h, 50.0f);
    EXPECT_THROW(find_hypotheses(test_device(), one.points, one.filtered_depth, opt, nullptr, &wider),
                 InputError);
  }
}
