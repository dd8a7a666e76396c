// The bin renderer's compute shaders against their C++ references on random input
// (bin_gbuffer.comp, bin_coverage.comp), with the validation layer on, and the plain C++
// pieces around them: the noise generator, BOP boxes, atlas packing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <algorithm>
#include <random>

#include "host/core/error.hpp"
#include "synth/render/bin_atlas.hpp"
#include "synth/render/bin_coverage.hpp"
#include "synth/render/bin_gbuffer.hpp"
#include "synth/render/bin_noise.hpp"

using namespace binpick;

namespace {
const bool validation_on = [] { return setenv("BINPICK_VK_VALIDATION", "1", 1) == 0; }();

GBufferInput random_input(std::uint32_t w, std::uint32_t h, std::uint32_t parts, std::mt19937& rng) {
  std::uniform_real_distribution<float> b01(0.0f, 1.0f), n11(-1.0f, 1.0f);
  // Some ids out of range (background), some the bin's (a surface of no part).
  std::uniform_int_distribution<std::uint32_t> id(0, parts + 3);
  const std::size_t n = std::size_t(w) * h;
  GBufferInput in{std::vector<float>(n), std::vector<std::uint32_t>(n), std::vector<float>(4 * n)};
  for (std::size_t i = 0; i < n; ++i) {
    in.zbuffer[i] = b01(rng);
    in.ids[i] = id(rng);
    if (in.ids[i] == parts + 3) in.ids[i] = kStaticSurfaceId;
    for (int k = 0; k < 4; ++k) in.raster_normals[4 * i + k] = n11(rng);
  }
  in.zbuffer[0] = 1.0f;                       // the far plane: background whatever the id
  if (n > 2) in.zbuffer[1] = NAN, in.ids[1] = 1;
  if (n > 3) in.raster_normals[12] = in.raster_normals[13] = in.raster_normals[14] = 0.0f;
  return in;
}

// Floats: the device may fuse and round differently: a few ulps, and for the noise, the
// precision of llvmpipe's log and cos (relative 1e-5 of sigma).
void expect_same(const GBufferOutput& got, const GBufferOutput& want, float sigma) {
  ASSERT_EQ(got.depth_mm.size(), want.depth_mm.size());
  for (std::size_t i = 0; i < want.depth_mm.size(); ++i) {
    const float tol = 4e-6f * std::fabs(want.depth_mm[i]) + 1e-4f * sigma;
    ASSERT_NEAR(got.depth_mm[i], want.depth_mm[i], tol) << i;
    for (int k = 0; k < 3; ++k) {
      ASSERT_NEAR(got.points[3 * i + k], want.points[3 * i + k], 2 * tol + 1e-6f) << i;
      ASSERT_NEAR(got.normals[3 * i + k], want.normals[3 * i + k], 1e-5f) << i;
    }
    ASSERT_NEAR(int(got.gray[i]), int(want.gray[i]), 1) << i;  // rounding at .5 boundaries
    ASSERT_EQ(got.instance[i], want.instance[i]) << i;
  }
  EXPECT_EQ(got.visible.count, want.visible.count);
  EXPECT_EQ(got.visible.box, want.visible.box);
}
}  // namespace

TEST(BinGBuffer, MatchesReferenceOnRandomInput) {
  ASSERT_TRUE(validation_on);
  std::mt19937 rng(5);
  for (auto [w, h, parts] : {std::tuple{1u, 1u, 1u}, {17u, 33u, 5u}, {160u, 90u, 40u}}) {
    const GBufferInput in = random_input(w, h, parts, rng);
    for (float sigma : {0.0f, 3.0f}) {
      RenderCamera cam{w, h, 1500.0, 1490.0, (w - 1) / 2.0, (h - 1) / 2.0, 350.0, 1050.0};
      const GBufferParams p = gbuffer_params(cam, sigma, 0x123456789abcdefull, parts);
      SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + " sigma " + std::to_string(sigma));
      expect_same(bin_gbuffer(in, p), bin_gbuffer_reference(in, p), sigma);
    }
  }
}

TEST(BinGBuffer, BackgroundIsZeroAndSurfaceIsLit) {
  std::mt19937 rng(6);
  const GBufferInput in = random_input(40, 30, 3, rng);
  RenderCamera cam{40, 30, 100.0, 100.0, 19.5, 14.5, 350.0, 1050.0};
  const auto out = bin_gbuffer(in, gbuffer_params(cam, 0.0, 0, 3));
  std::size_t bin_pixels = 0;
  for (std::size_t i = 0; i < in.ids.size(); ++i) {
    const bool part = in.ids[i] >= 1 && in.ids[i] <= 3 && in.zbuffer[i] < 1.0f;
    const bool bin = in.ids[i] == kStaticSurfaceId && in.zbuffer[i] < 1.0f;
    const bool surface = part || bin;
    bin_pixels += bin;
    EXPECT_EQ(out.instance[i] >= 0, part) << i;  // the bin's pixels are no part's
    EXPECT_EQ(out.depth_mm[i] > 0, surface) << i;
    if (!surface) {
      EXPECT_EQ(out.depth_mm[i], 0.0f);
      EXPECT_EQ(out.gray[i], 0);
      EXPECT_EQ(out.points[3 * i + 2], 0.0f);
    } else {
      EXPECT_GE(out.gray[i], 51);  // the ambient term
      EXPECT_GE(out.depth_mm[i], 350.0f * 0.9999f);
      EXPECT_LE(out.depth_mm[i], 1050.0f * 1.0001f);
      const Eigen::Vector3f n(&out.normals[3 * i]), p(&out.points[3 * i]);
      EXPECT_NEAR(n.norm(), 1.0f, 1e-5f);
      EXPECT_LE(n.dot(p), 0.0f);  // faces the camera
    }
  }
  EXPECT_GT(bin_pixels, 0u);
  // Visible counts are the parts' pixels alone.
  std::uint32_t counted = 0;
  for (const std::uint32_t c : out.visible.count) counted += c;
  EXPECT_EQ(counted, std::size_t(std::count_if(out.instance.begin(), out.instance.end(),
                                               [](std::int32_t i) { return i >= 0; })));
}

TEST(BinNoise, IsStandardNormalAndSeeded) {
  double sum = 0, sum2 = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double g = pixel_gaussian(42, std::uint32_t(i));
    ASSERT_TRUE(std::isfinite(g));
    sum += g, sum2 += g * g;
  }
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(std::sqrt(sum2 / n), 1.0, 0.01);
  EXPECT_EQ(pixel_hash(42, 7), pixel_hash(42, 7));
  EXPECT_NE(pixel_hash(42, 7), pixel_hash(43, 7));
  EXPECT_NE(pixel_hash(42, 7), pixel_hash(42ull | (1ull << 40), 7));  // the seed's high word counts
}

TEST(BinCoverage, MatchesReferenceOnRandomAtlas) {
  std::mt19937 rng(7);
  for (auto [w, h, parts] : {std::tuple{1u, 1u, 1u}, {33u, 17u, 4u}, {300u, 200u, 60u}}) {
    std::uniform_int_distribution<std::uint32_t> id(0, parts + 1);
    std::uniform_int_distribution<int> shift(-500, 1500);
    std::vector<std::uint32_t> atlas(std::size_t(w) * h);
    for (auto& a : atlas) a = id(rng);
    std::vector<std::array<int, 2>> shifts(parts);
    for (auto& s : shifts) s = {shift(rng), shift(rng)};
    const CoverageParams p{w, h, parts};
    const PartPixels got = coverage_counts(atlas, shifts, p), want = coverage_counts_reference(atlas, shifts, p);
    EXPECT_EQ(got.count, want.count);
    EXPECT_EQ(got.box, want.box);
  }
}

TEST(BopBBox, FollowsBopToolkit) {
  EXPECT_EQ(bop_bbox(kEmptyBox), (std::array<int, 4>{-1, -1, -1, -1}));
  EXPECT_EQ(bop_bbox({3, 4, 3, 4}), (std::array<int, 4>{3, 4, 0, 0}));
  EXPECT_EQ(bop_bbox({3, 4, 10, 6}), (std::array<int, 4>{3, 4, 7, 2}));
}

TEST(PackAtlas, TilesAreDisjointAndInside) {
  std::mt19937 rng(8);
  std::uniform_int_distribution<int> size(0, 150);
  std::vector<PixelRect> rects(400);
  for (auto& r : rects) r = {0, 0, size(rng), size(rng)};
  const auto batches = pack_atlas(rects, 1024, 512);
  EXPECT_GT(batches.size(), 1u);
  std::vector<int> placed(rects.size(), 0);
  for (const auto& b : batches) {
    EXPECT_LE(b.width, 1024);
    EXPECT_LE(b.height, 512);
    for (std::size_t i = 0; i < b.tiles.size(); ++i) {
      const auto& t = b.tiles[i];
      ++placed[t.part];
      EXPECT_GE(t.atlas_x, 0);
      EXPECT_GE(t.atlas_y, 0);
      EXPECT_LE(t.atlas_x + t.image.w, b.width);
      EXPECT_LE(t.atlas_y + t.image.h, b.height);
      for (std::size_t j = 0; j < i; ++j) {
        const auto& o = b.tiles[j];
        const bool apart = t.atlas_x + t.image.w <= o.atlas_x || o.atlas_x + o.image.w <= t.atlas_x ||
                           t.atlas_y + t.image.h <= o.atlas_y || o.atlas_y + o.image.h <= t.atlas_y;
        ASSERT_TRUE(apart) << t.part << " overlaps " << o.part;
      }
    }
  }
  for (std::size_t i = 0; i < rects.size(); ++i) EXPECT_EQ(placed[i], rects[i].empty() ? 0 : 1) << i;
  EXPECT_THROW(pack_atlas({{0, 0, 2000, 10}}, 1024, 512), InputError);
}
