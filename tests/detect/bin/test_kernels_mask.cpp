// The "may be used" mask (kernels/scene_mask.cl: scene_mask, masked_points), its use by the
// highest points (hyp_exclude_masked) and by the crops (crop_rect_count_masked,
// crop_rect_scatter_masked), and the bin fit's plane scoring and sampling (kernels/bin_planes.cl:
// bin_plane_inliers, bin_sample_grid), each against its plain C++ reference on random input: the
// predicates are shared (kernels/scene_mask_shared.h, FP_CONTRACT OFF), so masks, counts, pixels
// and points compare exactly. Also the degenerate inputs: no box, an empty box, no data.
#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <tuple>

#include <Eigen/Geometry>

#include "host/core/error.hpp"
#include "host/detect/bin/bin_planes.hpp"
#include "host/detect/hypotheses/hypotheses.hpp"
#include "host/detect/scene/scene_crop.hpp"
#include "host/detect/scene/scene_lowpass.hpp"
#include "host/detect/bin/scene_mask.hpp"
#include "tests/support/kernel_refs.hpp"

using namespace binpick;
using namespace binpick::test;

namespace {

// A box turned at random about a random axis, centred near the image's points, of random size.
RegionBox random_box(std::mt19937& rng, const PointImage& pts) {
  std::uniform_real_distribution<float> U(-1.0f, 1.0f);
  std::uniform_int_distribution<std::size_t> pick(0, pts.xyzw.size() / 4 - 1);
  RegionBox b;
  b.R = Eigen::AngleAxisf(3.0f * U(rng), Eigen::Vector3f(U(rng), U(rng), U(rng) + 2).normalized())
            .toRotationMatrix();
  const float* p = &pts.xyzw[4 * pick(rng)];
  b.t = Eigen::Vector3f(p[0], p[1], p[2]) + 20.0f * Eigen::Vector3f(U(rng), U(rng), U(rng));
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = -150.0f + 100.0f * U(rng);
    b.hi[a] = b.lo[a] + 20.0f + 150.0f * (U(rng) + 1.0f);
  }
  return b;
}

// A point exactly on a box's face (kept: bounds are included): the box is axis-aligned with the
// origin at 0, so q = p and the comparison is exact.
void put_on_face(PointImage& pts, std::size_t i, const RegionBox& b) {
  pts.xyzw[4 * i] = b.hi.x();
  pts.xyzw[4 * i + 1] = 0.5f * (b.lo.y() + b.hi.y());
  pts.xyzw[4 * i + 2] = b.lo.z();
  pts.xyzw[4 * i + 3] = 1.0f;
}

}  // namespace

TEST(MaskKernels, scene_mask_matches_reference) {
  auto& dev = ocl::Device::shared();
  std::mt19937 rng(71);
  int kept_some = 0, dropped_some = 0;
  for (auto [w, h, holes] : {std::tuple{1u, 1u, 0.0f}, {37u, 23u, 0.1f}, {160u, 120u, 0.3f},
                             {301u, 77u, 0.7f}}) {
    PointImage pts = random_point_image(rng, w, h, holes);
    for (int t = 0; t < 8; ++t) {
      SceneRegion region;
      if (t % 4 != 1) region.roi = random_box(rng, pts);
      if (t % 4 != 2) region.bin = random_box(rng, pts);
      if (t == 3) {  // axis-aligned at the origin, a point exactly on its face
        RegionBox b;
        b.lo = {-500, -500, 500}, b.hi = {500, 500, 700};
        region.roi = b;
        region.bin.reset();
        put_on_face(pts, pts.xyzw.size() / 8, b);
      }
      if (t == 5) region.bin->hi = region.bin->lo;  // a flat box: keeps only its plane
      const std::vector<std::uint8_t> want = scene_mask_reference(pts, region);
      const std::vector<std::uint8_t> got = scene_mask(dev, pts, region);
      ASSERT_EQ(got, want) << w << "x" << h << " case " << t;
      for (std::size_t i = 0; i < want.size(); ++i) {
        if (pts.xyzw[4 * i + 3] == 0.0f) {
          EXPECT_EQ(want[i], 0) << "a pixel without data was kept";
        }
        kept_some += want[i] == 1;
        dropped_some += want[i] == 0 && pts.xyzw[4 * i + 3] != 0.0f;
      }
      if (t == 3) {
        EXPECT_EQ(want[pts.xyzw.size() / 8], 1) << "a point on the face is kept";
      }
    }
    // No box: every pixel with data.
    const std::vector<std::uint8_t> all = scene_mask(dev, pts, SceneRegion{});
    for (std::size_t i = 0; i < all.size(); ++i) EXPECT_EQ(all[i], pts.xyzw[4 * i + 3] != 0.0f);
  }
  EXPECT_GT(kept_some, 100);
  EXPECT_GT(dropped_some, 100);
  SceneRegion bad;
  bad.roi = RegionBox{};
  bad.roi->lo.x() = NAN;
  EXPECT_THROW(to_shared(bad), InputError);
}

TEST(MaskKernels, masked_points_match_reference) {
  auto& dev = ocl::Device::shared();
  std::mt19937 rng(72);
  for (auto [w, h] : {std::pair{1u, 1u}, {64u, 48u}, {211u, 97u}}) {
    const PointImage pts = random_point_image(rng, w, h, 0.2f);
    SceneRegion region;
    region.roi = random_box(rng, pts);
    const std::size_t n = std::size_t(w) * h;
    ocl::Buffer<float> p = upload(dev, pts.xyzw);
    const ocl::Buffer<std::uint8_t> mask = scene_mask(dev, p, n, region);
    ocl::Buffer<float> out(dev, 4 * n);
    out.fill(dev, -1.0f);
    enqueue_masked_points(dev, p, mask, n, out);
    const std::vector<float> got = out.read(dev);
    const PointImage want = masked_points_reference(pts, mask.read(dev));
    ASSERT_EQ(got.size(), want.xyzw.size());
    for (std::size_t i = 0; i < got.size(); ++i) ASSERT_TRUE(same_bits(got[i], want.xyzw[i])) << i;
  }
}

// Highest points with a mask: the routine equals the reference, no hypothesis is on a masked
// pixel, and an all-zero mask gives none; the low-pass of the kept points is what the detector
// hands it (so a masked pixel also has no filtered depth).
TEST(MaskKernels, hypotheses_never_on_masked_pixels) {
  auto& dev = ocl::Device::shared();
  std::mt19937 rng(73);
  for (int t = 0; t < 6; ++t) {
    const PointImage pts = random_point_image(rng, 160, 120, t % 2 ? 0.7f : 0.1f);
    SceneRegion region;
    region.roi = random_box(rng, pts);
    const std::vector<std::uint8_t> mask = scene_mask_reference(pts, region);
    HypothesisOptions ho;
    ho.count = 8;
    ho.exclusion_radius = 15.0f;
    for (bool masked_lowpass : {false, true}) {
      const std::vector<float> filtered = lowpass_depth_reference(
          masked_lowpass ? masked_points_reference(pts, mask) : pts, 3);
      const auto want = find_hypotheses_reference(pts, filtered, ho, &mask);
      const auto got = find_hypotheses(dev, pts, filtered, ho, &mask);
      ASSERT_EQ(got.size(), want.size());
      for (std::size_t k = 0; k < got.size(); ++k) {
        EXPECT_EQ(got[k].pixel, want[k].pixel);
        EXPECT_TRUE(same_bits(got[k].depth, want[k].depth));
        EXPECT_EQ(mask[got[k].pixel], 1) << "hypothesis " << k << " on a masked pixel";
      }
    }
  }
  const PointImage pts = random_point_image(rng, 40, 30, 0.0f);
  const std::vector<std::uint8_t> none(40 * 30, 0);
  const std::vector<float> filtered = lowpass_depth_reference(pts, 2);
  EXPECT_TRUE(find_hypotheses(dev, pts, filtered, {}, &none).empty());
  EXPECT_TRUE(find_hypotheses_reference(pts, filtered, {}, &none).empty());
  const std::vector<std::uint8_t> short_mask(10, 1);
  EXPECT_THROW(find_hypotheses(dev, pts, filtered, {}, &short_mask), InputError);
}

// The masked crop: equal to the reference pixel for pixel, and no masked pixel inside.
TEST(MaskKernels, masked_crop_matches_reference) {
  auto& dev = ocl::Device::shared();
  std::mt19937 rng(74);
  std::size_t total = 0;
  for (int t = 0; t < 10; ++t) {
    const PointImage pts = random_point_image(rng, 160, 120, t % 2 ? 0.7f : 0.05f, 0.5f, 150.0f);
    const bp_camera cam{150.0f, 150.0f, 79.5f, 59.5f, 1.0f, 160, 120, 0};
    SceneRegion region;
    region.roi = random_box(rng, pts);
    const std::vector<std::uint8_t> mask = scene_mask_reference(pts, region);
    CropOptions opt;
    std::uniform_int_distribution<std::size_t> pick(0, 160 * 120 - 1);
    const float* c = &pts.xyzw[4 * pick(rng)];
    opt.centre = {c[0], c[1], c[2] == 0.0f ? 700.0f : c[2]};
    opt.radius = 40.0f + 10.0f * t;
    ocl::Buffer<float> p = upload(dev, pts.xyzw);
    const ocl::Buffer<std::uint8_t> m = upload(dev, mask);
    const CroppedPixels got = crop_pixels(dev, p, cam, opt, &m);
    const CroppedPixels want = crop_pixels_reference(pts, opt, &mask);
    ASSERT_EQ(got.pixels, want.pixels);
    ASSERT_EQ(got.points.size(), want.points.size());
    for (std::size_t i = 0; i < got.points.size(); ++i) EXPECT_EQ(got.points[i], want.points[i]);
    for (std::uint32_t i : got.pixels) EXPECT_EQ(mask[i], 1);
    // Without a mask it is today's crop; with an all-ones mask the same.
    const std::vector<std::uint8_t> ones(mask.size(), 1);
    const ocl::Buffer<std::uint8_t> all = upload(dev, ones);
    EXPECT_EQ(crop_pixels(dev, p, cam, opt, &all).pixels, crop_pixels(dev, p, cam, opt).pixels);
    total += got.pixels.size();
  }
  EXPECT_GT(total, 50u);
}

TEST(MaskKernels, plane_inliers_match_reference) {
  auto& dev = ocl::Device::shared();
  std::mt19937 rng(75);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f);
  // Sizes around the kernel's blocks of eight points (the tail is scanned one by one).
  for (std::size_t n : {0ul, 1ul, 7ul, 8ul, 9ul, 16ul, 777ul, 20000ul}) {
    std::vector<Eigen::Vector3f> pts;
    for (std::size_t i = 0; i < n; ++i)
      pts.emplace_back(300 * U(rng), 300 * U(rng), 900 + 100 * U(rng));
    std::vector<bp_plane> planes;
    for (int k = 0; k < 37; ++k) {
      const Eigen::Vector3f nrm = Eigen::Vector3f(U(rng), U(rng), U(rng) + 2).normalized();
      planes.push_back({nrm.x(), nrm.y(), nrm.z(), -(900 + 100 * U(rng)) * nrm.z()});
    }
    planes.push_back({0, 0, 1, -900});  // axis-aligned: points at z = 900 +- tol exactly
    if (n > 0) pts[0] = {1, 2, 905};    // exactly at tol: an inlier
    const auto want = count_plane_inliers_reference(pts, planes, 5.0f);
    EXPECT_EQ(count_plane_inliers(dev, pts, planes, 5.0f), want) << n;
    if (n > 0) {
      EXPECT_GE(want.back(), 1u);
    }
  }
  EXPECT_TRUE(count_plane_inliers(dev, {}, {}, 1.0f).empty());
}

// The bin fit's samples gathered on the device (bin_sample_grid) are the host's sample_points
// of the read-back image: the same points, pixels and stride, on images with few and many holes,
// one pixel, no data at all, and strides from 1 (a small image) up.
TEST(MaskKernels, sample_grid_matches_sample_points) {
  auto& dev = ocl::Device::shared();
  std::mt19937 rng(76);
  for (auto [w, h, holes, max_points] :
       {std::tuple{1u, 1u, 0.0f, 40000ul}, {1u, 1u, 1.0f, 40000ul}, {37u, 23u, 0.3f, 40000ul},
        {160u, 120u, 0.05f, 1000ul}, {301u, 77u, 0.9f, 500ul}, {64u, 64u, 0.0f, 1ul}}) {
    const PointImage pts = random_point_image(rng, w, h, holes);
    std::size_t valid = 0;
    for (std::size_t i = 0; i < std::size_t(w) * h; ++i) valid += pts.xyzw[4 * i + 3] != 0.0f;
    const PlaneSamples want = sample_points(pts.xyzw, w, h, max_points);
    const PlaneSamples got = sample_points(dev, upload(dev, pts.xyzw), w, h, valid, max_points);
    const std::string at = std::to_string(w) + "x" + std::to_string(h);
    EXPECT_EQ(got.stride, want.stride) << at;
    EXPECT_EQ(got.stride, sample_stride(valid, max_points)) << at;
    EXPECT_EQ(got.width, w);
    EXPECT_EQ(got.height, h);
    ASSERT_EQ(got.points, want.points) << at;
    EXPECT_EQ(got.u, want.u) << at;
    EXPECT_EQ(got.v, want.v) << at;
    if (holes == 1.0f) {
      EXPECT_TRUE(got.points.empty());
    }
  }
  EXPECT_EQ(sample_stride(0, 40000), 1u);
  EXPECT_EQ(sample_stride(1440000, 40000), 6u);
  EXPECT_THROW(sample_points(dev, ocl::Buffer<float>(dev, 4), 2, 2, 4), std::logic_error);
}
