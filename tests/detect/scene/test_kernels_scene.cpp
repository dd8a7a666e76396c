// The three passes of the low-pass filter and the points moved to its depth
// (kernels/scene_lowpass.cl), and the fixed-radius normal kernels (kernels/scene_normals.cl),
// each launched by itself on random point images and
// compared with a plain C++ reference of that one step (tests/support/kernel_refs.hpp, and
// host/detect/scene/scene_normals.hpp's references).
//
// Low-pass: the same float additions in the same order and one division on both sides: exact
// (as tests/detect/scene/test_scene_prep.cpp's Lowpass.EqualsTheReferenceExactly holds the composed routine).
// Normals: bit for bit the generic-radius kernels (same normal_at, the radius a constant), and
// within 0.5 degrees of the double-precision Eigen reference, where a disagreement (in the
// direction or in having a normal at all) is allowed only at an ill-conditioned pixel: the two
// smallest eigenvalues within 1e-3 of the largest, or the middle one within twice the
// degeneracy ratio (the tolerance of tests/detect/scene/test_scene_prep.cpp's Normals tests); and opposite
// orientations only where the plane is seen edge-on (the normal within 0.5 degrees of
// perpendicular to the pixel's ray: n . p < 0 is then decided by rounding), as in every pixel
// of a one-row image, whose points all lie in a plane through the camera centre.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>

#include "host/core/error.hpp"
#include "host/detect/scene/scene_lowpass.hpp"
#include "host/detect/scene/scene_normals.hpp"
#include "tests/support/kernel_refs.hpp"

using namespace binpick;
using namespace binpick::test;

namespace {

constexpr std::size_t kGuard = 8;
constexpr float kFloatCanary = -12345.0f;

struct ImageCase {
  u32 w, h;
  float holes, noise;
};
// Sizes that divide no work group (37 x 23, 1 x 50, 50 x 1), a single pixel, holes, noise.
const ImageCase kImages[] = {{1, 1, 0.0f, 0.0f},    {37, 23, 0.1f, 0.5f}, {1, 50, 0.1f, 0.5f},
                             {50, 1, 0.0f, 0.5f},   {160, 120, 0.05f, 0.5f},
                             {120, 90, 0.3f, 2.0f}};

bool ill_conditioned(const PointImage& pts, std::size_t i, int radius, float max_distance) {
  const Eigen::Vector3d ev =
      normal_window_eigenvalues(pts, int(i % pts.width), int(i / pts.width), radius, max_distance);
  return ev[1] < 2.0 * BP_NORMAL_DEGENERATE_RATIO * ev[2] || ev[1] - ev[0] < 1e-3 * ev[2];
}

float angle_deg(const float* a, const float* b) {
  const Eigen::Vector3d x(a[0], a[1], a[2]), y(b[0], b[1], b[2]);
  return float(std::atan2(x.cross(y).norm(), x.dot(y)) * 180.0 / M_PI);
}

struct NormalStats {
  int compared = 0, ill = 0, edge_on = 0;
};

// got (device) against want (reference) at pixel i of pts; counts into stats.
void expect_normal_close(const PointImage& pts, std::size_t i, const float* g, const float* r,
                         const NormalOptions& opt, NormalStats& stats, const std::string& at) {
  if (g[3] == 0 && r[3] == 0) {
    for (int c = 0; c < 4; ++c) EXPECT_EQ(g[c], 0.0f) << at;  // no normal: all 0
    return;
  }
  if (g[3] == r[3] && angle_deg(g, r) < 0.5f) {
    ++stats.compared;
    EXPECT_EQ(g[3], 1.0f) << at;
    EXPECT_NEAR(Eigen::Vector3f(g[0], g[1], g[2]).norm(), 1.0f, 1e-5f) << at;
    const float* p = &pts.xyzw[4 * i];
    EXPECT_LE(g[0] * p[0] + g[1] * p[1] + g[2] * p[2], 0.0f) << at;  // towards the camera
    return;
  }
  // Opposite orientations: the sign (n . p < 0) is decided by rounding where the plane is seen
  // edge-on, i.e. where the normal lies within the 0.5 degrees of perpendicular to the ray.
  const Eigen::Vector3f ray = Eigen::Vector3f(pts.xyzw[4 * i], pts.xyzw[4 * i + 1], pts.xyzw[4 * i + 2]).normalized();
  if (g[3] == r[3] && angle_deg(g, r) > 179.5f &&
      std::fabs(Eigen::Vector3f(r[0], r[1], r[2]).dot(ray)) <= std::sin(0.5f * float(M_PI) / 180)) {
    ++stats.edge_on;
    return;
  }
  ++stats.ill;
  EXPECT_TRUE(ill_conditioned(pts, i, opt.radius, opt.max_distance))
      << at << " valid " << g[3] << "/" << r[3] << " angle " << angle_deg(g, r);
}

std::string fixed_kernel(const char* base, int radius) { return base + std::to_string(radius); }

}  // namespace

TEST(LowpassKernels, lowpass_pairs_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel plain = dev.kernel("scene_lowpass.cl", "lowpass_pairs");
  cl::Kernel masked = dev.kernel("scene_lowpass.cl", "lowpass_pairs_masked");
  std::mt19937 rng(700);
  std::bernoulli_distribution keep(0.6);
  for (const ImageCase& c : kImages) {
    const PointImage pts = random_point_image(rng, c.w, c.h, c.holes, c.noise);
    const std::size_t n = std::size_t(c.w) * c.h;
    ocl::Buffer<float> points = upload(dev, pts.xyzw);
    std::vector<std::uint8_t> mask(n);
    for (auto& m : mask) m = keep(rng) ? 1 : 0;
    ocl::Buffer<std::uint8_t> m = upload(dev, mask);
    for (bool with_mask : {false, true}) {
      ocl::Buffer<float> pairs =
          guarded_buffer(dev, std::vector<float>(2 * n, kFloatCanary), kGuard, kFloatCanary);
      if (with_mask)
        ocl::launch_local(dev, masked, n, 64, points, m, cl_uint(n), pairs);
      else
        ocl::launch_local(dev, plain, n, 64, points, cl_uint(n), pairs);
      std::vector<float> want = lowpass_pairs_reference(pts.xyzw, with_mask ? &mask : nullptr);
      want.insert(want.end(), kGuard, kFloatCanary);
      ASSERT_EQ(pairs.read(dev), want) << c.w << "x" << c.h << " mask " << with_mask;
    }
  }
}

// The rows of the pairs are the row sums of the valid points themselves.
TEST(LowpassKernels, lowpass_rows_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("scene_lowpass.cl", "lowpass_rows");
  std::mt19937 rng(701);
  for (const ImageCase& c : kImages) {
    const PointImage pts = random_point_image(rng, c.w, c.h, c.holes, c.noise);
    ocl::Buffer<float> pairs = upload(dev, lowpass_pairs_reference(pts.xyzw));
    for (int radius : {0, 1, 5, 64}) {
      ocl::Buffer<float> row_sums =
          guarded_buffer(dev, std::vector<float>(2 * std::size_t(c.w) * c.h, kFloatCanary), kGuard, kFloatCanary);
      ocl::launch(dev, k, lowpass_work_items(c.w, c.h), pairs, c.w, c.h, cl_int(radius), row_sums);
      std::vector<float> want = lowpass_rows_reference(pts.xyzw, int(c.w), int(c.h), radius);
      want.insert(want.end(), kGuard, kFloatCanary);
      ASSERT_EQ(row_sums.read(dev), want) << c.w << "x" << c.h << " r " << radius;
    }
  }
}

TEST(LowpassKernels, lowpass_cols_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("scene_lowpass.cl", "lowpass_cols");
  std::mt19937 rng(702);
  std::uniform_real_distribution<float> sum(0.0f, 20000.0f);
  for (const ImageCase& c : kImages) {
    const PointImage pts = random_point_image(rng, c.w, c.h, c.holes, c.noise);
    const std::size_t n = std::size_t(c.w) * c.h;
    ocl::Buffer<float> pairs = upload(dev, lowpass_pairs_reference(pts.xyzw));
    for (int radius : {0, 1, 5, 64}) {
      // Random row sums: any sum, an integer count of at least 1 (so every column count is).
      std::uniform_int_distribution<int> count(1, 2 * radius + 1);
      std::vector<float> row_sums(2 * n);
      for (std::size_t i = 0; i < n; ++i) row_sums[2 * i] = sum(rng), row_sums[2 * i + 1] = float(count(rng));
      ocl::Buffer<float> rs = upload(dev, row_sums);
      ocl::Buffer<float> filtered = guarded_buffer(dev, std::vector<float>(n, kFloatCanary), kGuard, kFloatCanary);
      ocl::launch(dev, k, lowpass_work_items(c.w, c.h), pairs, rs, c.w, c.h, cl_int(radius), filtered);
      std::vector<float> want = lowpass_cols_reference(pts.xyzw, row_sums, int(c.w), int(c.h), radius);
      want.insert(want.end(), kGuard, kFloatCanary);
      ASSERT_EQ(filtered.read(dev), want) << c.w << "x" << c.h << " r " << radius;
    }
  }
}

// The points moved to the low-passed depth: exactly the reference's floats, on images with
// holes, pixels without a low-passed depth (0: masked out) and an image without any data (the
// points as they are); the tail of the output untouched.
TEST(LowpassKernels, lowpass_points_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel kernel = dev.kernel("scene_lowpass.cl", "lowpass_points");
  std::mt19937 rng(704);
  std::bernoulli_distribution masked(0.3);
  std::normal_distribution<float> smooth(0.0f, 2.0f);
  std::vector<PointImage> images;
  for (const ImageCase& c : kImages) images.push_back(random_point_image(rng, c.w, c.h, c.holes, c.noise));
  images.push_back(PointImage{9, 7, std::vector<float>(4 * 9 * 7, 0.0f)});
  for (std::size_t im = 0; im < images.size(); ++im) {
    const PointImage& pts = images[im];
    const std::size_t n = std::size_t(pts.width) * pts.height;
    std::vector<float> filtered(n, 0.0f);
    for (std::size_t i = 0; i < n; ++i)
      if (pts.xyzw[4 * i + 3] != 0.0f && !masked(rng))
        filtered[i] = std::max(1.0f, pts.xyzw[4 * i + 2] + smooth(rng));
    ocl::Buffer<float> points = upload(dev, pts.xyzw), f = upload(dev, filtered);
    std::vector<float> want = lowpass_points_reference(pts.xyzw, filtered);
    if (im + 1 == images.size()) {
      EXPECT_EQ(want, pts.xyzw);  // no data: as it is
    }
    want.insert(want.end(), kGuard, kFloatCanary);
    // The kernel by itself, in padded work groups of 64, and through the routine.
    ocl::Buffer<float> out =
        guarded_buffer(dev, std::vector<float>(4 * n, kFloatCanary), kGuard, kFloatCanary);
    ocl::launch_local(dev, kernel, n, 64, points, f, cl_uint(n), out);
    ASSERT_EQ(out.read(dev), want) << pts.width << "x" << pts.height;
    ocl::Buffer<float> routine =
        guarded_buffer(dev, std::vector<float>(4 * n, kFloatCanary), kGuard, kFloatCanary);
    enqueue_lowpass_points(dev, points, f, n, routine);
    ASSERT_EQ(routine.read(dev), want) << pts.width << "x" << pts.height;
  }
  EXPECT_THROW(lowpass_points_reference(std::vector<float>(8, 1.0f), {1.0f}), InputError);
}

// The routine's three passes (enqueue_lowpass_depth) in sequence, each checked, on degenerate
// images too (all pixels without data: all 0; one valid pixel: its own depth), launched in
// padded work groups of 64 (the extra work items must write nothing).
TEST(LowpassKernels, PassesInSequenceAndDegenerateImages) {
  auto& dev = ocl::Device::shared();
  cl::Kernel to_pairs = dev.kernel("scene_lowpass.cl", "lowpass_pairs");
  cl::Kernel rows = dev.kernel("scene_lowpass.cl", "lowpass_rows");
  cl::Kernel cols = dev.kernel("scene_lowpass.cl", "lowpass_cols");
  std::mt19937 rng(703);
  std::vector<PointImage> images;
  images.push_back(PointImage{21, 13, std::vector<float>(4 * 21 * 13, 0.0f)});
  images.push_back(images.back());
  images.back().xyzw[4 * 100 + 2] = 777.0f, images.back().xyzw[4 * 100 + 3] = 1.0f;
  images.push_back(random_point_image(rng, 97, 61, 0.1f, 1.0f));
  for (std::size_t im = 0; im < images.size(); ++im) {
    const PointImage& pts = images[im];
    const std::size_t n = std::size_t(pts.width) * pts.height;
    ocl::Buffer<float> points = upload(dev, pts.xyzw);
    for (int radius : {0, 3, 8}) {
      ocl::Buffer<float> row_sums = guarded_buffer(dev, std::vector<float>(2 * n, kFloatCanary), kGuard, kFloatCanary);
      ocl::Buffer<float> filtered = guarded_buffer(dev, std::vector<float>(n, kFloatCanary), kGuard, kFloatCanary);
      ocl::Buffer<float> pairs = guarded_buffer(dev, std::vector<float>(2 * n, kFloatCanary), kGuard, kFloatCanary);
      ocl::launch_local(dev, to_pairs, n, 64, points, cl_uint(n), pairs);
      std::vector<float> want_pairs = lowpass_pairs_reference(pts.xyzw);
      std::vector<float> got_pairs = pairs.read(dev);
      ASSERT_EQ(std::vector<float>(got_pairs.begin(), got_pairs.begin() + 2 * n), want_pairs) << im;
      ocl::launch_local(dev, rows, lowpass_work_items(pts.width, pts.height), 64, pairs, pts.width, pts.height, cl_int(radius), row_sums);
      std::vector<float> want_rows = lowpass_rows_reference(pts.xyzw, int(pts.width), int(pts.height), radius);
      std::vector<float> got_rows = row_sums.read(dev);
      ASSERT_EQ(std::vector<float>(got_rows.begin(), got_rows.begin() + 2 * n), want_rows) << im << " " << radius;
      ocl::launch_local(dev, cols, lowpass_work_items(pts.width, pts.height), 64, pairs, row_sums, pts.width, pts.height, cl_int(radius), filtered);
      std::vector<float> want = lowpass_cols_reference(pts.xyzw, got_rows, int(pts.width), int(pts.height), radius);
      EXPECT_EQ(want, lowpass_depth_reference(pts, radius));
      want.insert(want.end(), kGuard, kFloatCanary);
      want_rows.insert(want_rows.end(), kGuard, kFloatCanary);
      want_pairs.insert(want_pairs.end(), kGuard, kFloatCanary);
      ASSERT_EQ(pairs.read(dev), want_pairs) << im;  // tails untouched
      ASSERT_EQ(row_sums.read(dev), want_rows) << im << " " << radius;
      ASSERT_EQ(filtered.read(dev), want) << im << " " << radius;
      if (im == 0) {
        EXPECT_EQ(std::count(want.begin(), want.begin() + n, 0.0f), std::ptrdiff_t(n));
      }
      if (im == 1) {
        EXPECT_EQ(want[100], 777.0f);
      }
    }
  }
}

TEST(NormalKernels, normals_from_points_r_matches_reference) {
  auto& dev = ocl::Device::shared();
  std::mt19937 rng(704);
  NormalStats stats;
  for (int radius : {1, 2, 3}) {
    // normals_from_points_r1, _r2, _r3, and the generic kernel they must equal bit for bit.
    cl::Kernel fixed = dev.kernel("scene_normals.cl", fixed_kernel("normals_from_points_r", radius));
    cl::Kernel generic = dev.kernel("scene_normals.cl", "normals_from_points");
    for (const ImageCase& c : kImages) {
      const PointImage pts = random_point_image(rng, c.w, c.h, c.holes, c.noise);
      const std::size_t n = std::size_t(c.w) * c.h;
      const NormalOptions opt{radius, 20.0f};
      ocl::Buffer<float> points = upload(dev, pts.xyzw);
      ocl::Buffer<float> out = guarded_buffer(dev, std::vector<float>(4 * n, kFloatCanary), kGuard, kFloatCanary);
      ocl::Buffer<float> out_generic(dev, 4 * n);
      ocl::launch(dev, fixed, n, points, c.w, c.h, cl_int(radius), opt.max_distance, 0.0f, 0.0f, out);
      ocl::launch(dev, generic, n, points, c.w, c.h, cl_int(radius), opt.max_distance, 0.0f, 0.0f, out_generic);
      const std::vector<float> got = out.read(dev), got_generic = out_generic.read(dev);
      for (std::size_t i = 4 * n; i < got.size(); ++i) ASSERT_EQ(got[i], kFloatCanary);
      for (std::size_t i = 0; i < 4 * n; ++i)
        ASSERT_TRUE(same_bits(got[i], got_generic[i])) << "r " << radius << " float " << i;
      const PointImage want = normals_from_points_reference(pts, opt);
      for (std::size_t i = 0; i < n; ++i)
        expect_normal_close(pts, i, &got[4 * i], &want.xyzw[4 * i], opt, stats,
                            std::to_string(c.w) + "x" + std::to_string(c.h) + " r " +
                                std::to_string(radius) + " pixel " + std::to_string(i));
    }
  }
  EXPECT_GT(stats.compared, 50000);
  EXPECT_LT(stats.ill, stats.compared / 1000 + 5) << stats.ill << " of " << stats.compared;
  std::printf("normals within 0.5 deg: %d, edge-on flips: %d, ill-conditioned: %d\n",
              stats.compared, stats.edge_on, stats.ill);
}

TEST(NormalKernels, normals_at_pixels_r_matches_reference) {
  auto& dev = ocl::Device::shared();
  std::mt19937 rng(705);
  NormalStats stats;
  for (int radius : {1, 2, 3}) {
    cl::Kernel at_pixels = dev.kernel("scene_normals.cl", fixed_kernel("normals_at_pixels_r", radius));
    cl::Kernel full = dev.kernel("scene_normals.cl", fixed_kernel("normals_from_points_r", radius));
    cl::Kernel generic = dev.kernel("scene_normals.cl", "normals_at_pixels");
    for (const ImageCase& c : kImages) {
      const PointImage pts = random_point_image(rng, c.w, c.h, c.holes, c.noise);
      const std::size_t n = std::size_t(c.w) * c.h;
      const NormalOptions opt{radius, 20.0f};
      ocl::Buffer<float> points = upload(dev, pts.xyzw);
      ocl::Buffer<float> full_out(dev, 4 * n);
      ocl::launch(dev, full, n, points, c.w, c.h, cl_int(radius), opt.max_distance, 0.0f, 0.0f, full_out);
      const std::vector<float> whole = full_out.read(dev);
      // Lists of any order with repeats, lengths that are not multiples of the work group of 32.
      std::uniform_int_distribution<u32> P(0, u32(n - 1));
      for (std::size_t count : {1u, 31u, 33u, 2000u}) {
        std::vector<u32> pixels(count);
        for (auto& p : pixels) p = P(rng);
        ocl::Buffer<u32> list = upload(dev, pixels);
        ocl::Buffer<float> out = guarded_buffer(dev, std::vector<float>(4 * count, kFloatCanary), kGuard, kFloatCanary);
        ocl::Buffer<float> out_generic(dev, 4 * count);
        ocl::launch_local(dev, at_pixels, count, 32, points, c.w, c.h, cl_int(radius),
                          opt.max_distance, 0.0f, 0.0f, list, u32(count), out);  // as the routine
        ocl::launch_local(dev, generic, count, 32, points, c.w, c.h, cl_int(radius),
                          opt.max_distance, 0.0f, 0.0f, list, u32(count), out_generic);
        const std::vector<float> got = out.read(dev), got_generic = out_generic.read(dev);
        for (std::size_t i = 4 * count; i < got.size(); ++i) ASSERT_EQ(got[i], kFloatCanary);
        const std::vector<float> want = normals_at_pixels_reference(pts, pixels, opt);
        for (std::size_t j = 0; j < count; ++j) {
          for (int a = 0; a < 4; ++a) {
            ASSERT_TRUE(same_bits(got[4 * j + a], whole[4 * pixels[j] + a])) << j;
            ASSERT_TRUE(same_bits(got[4 * j + a], got_generic[4 * j + a])) << j;
          }
          expect_normal_close(pts, pixels[j], &got[4 * j], &want[4 * j], opt, stats,
                              std::to_string(c.w) + "x" + std::to_string(c.h) + " r " +
                                  std::to_string(radius) + " pixel " + std::to_string(pixels[j]));
        }
      }
    }
  }
  EXPECT_GT(stats.compared, 10000);
  EXPECT_LT(stats.ill, stats.compared / 1000 + 5) << stats.ill << " of " << stats.compared;
  std::printf("normals within 0.5 deg: %d, edge-on flips: %d, ill-conditioned: %d\n",
              stats.compared, stats.edge_on, stats.ill);
}

// Degenerate images give no normal (all 0): no pixel with data, a single valid pixel, one row of
// collinear points, fewer than 3 neighbours within max_distance; and padded work groups of 64
// for the full-image kernels (the extra work items must write nothing).
TEST(NormalKernels, DegenerateImagesGiveNoNormal) {
  auto& dev = ocl::Device::shared();
  std::mt19937 rng(706);
  std::vector<PointImage> images;
  images.push_back(PointImage{9, 7, std::vector<float>(4 * 63, 0.0f)});  // no data
  images.push_back(images.back());
  images.back().xyzw[4 * 31 + 2] = 500.0f, images.back().xyzw[4 * 31 + 3] = 1.0f;  // one pixel
  images.push_back(images.front());
  for (int u = 0; u < 9; ++u) {  // row 3: points on a line
    float* p = &images.back().xyzw[4 * (3 * 9 + u)];
    p[0] = 10.0f * u, p[1] = 5.0f, p[2] = 500.0f + 3.0f * u, p[3] = 1.0f;
  }
  images.push_back(random_point_image(rng, 9, 7, 0.0f, 0.0f));  // every pixel 100 mm deeper:
  for (std::size_t i = 0; i < 63; ++i) images.back().xyzw[4 * i + 2] += 100.0f * float(i);  // alone
  for (int radius : {1, 2, 3})
    for (std::size_t im = 0; im < images.size(); ++im) {
      const PointImage& pts = images[im];
      const std::size_t n = std::size_t(pts.width) * pts.height;
      const NormalOptions opt{radius, 20.0f};
      cl::Kernel fixed = dev.kernel("scene_normals.cl", fixed_kernel("normals_from_points_r", radius));
      cl::Kernel at_pixels = dev.kernel("scene_normals.cl", fixed_kernel("normals_at_pixels_r", radius));
      ocl::Buffer<float> points = upload(dev, pts.xyzw);
      ocl::Buffer<float> out = guarded_buffer(dev, std::vector<float>(4 * n, kFloatCanary), kGuard, kFloatCanary);
      ocl::launch_local(dev, fixed, n, 64, points, pts.width, pts.height, cl_int(radius), opt.max_distance, 0.0f, 0.0f, out);
      std::vector<u32> pixels(n);
      for (u32 i = 0; i < n; ++i) pixels[i] = i;
      ocl::Buffer<u32> list = upload(dev, pixels);
      ocl::Buffer<float> out_px = guarded_buffer(dev, std::vector<float>(4 * n, kFloatCanary), kGuard, kFloatCanary);
      ocl::launch_local(dev, at_pixels, n, 32, points, pts.width, pts.height, cl_int(radius),
                        opt.max_distance, 0.0f, 0.0f, list, u32(n), out_px);
      const std::vector<float> got = out.read(dev), got_px = out_px.read(dev);
      std::vector<float> want = normals_from_points_reference(pts, opt).xyzw;
      for (std::size_t i = 0; i < 4 * n; ++i) {
        ASSERT_EQ(got[i], 0.0f) << "image " << im << " r " << radius << " float " << i;
        ASSERT_EQ(want[i], 0.0f) << "image " << im << " r " << radius << " float " << i;
        ASSERT_EQ(got_px[i], 0.0f) << "image " << im << " r " << radius << " float " << i;
      }
      for (std::size_t i = 4 * n; i < got.size(); ++i) {
        ASSERT_EQ(got[i], kFloatCanary);
        ASSERT_EQ(got_px[i], kFloatCanary);
      }
    }
}
