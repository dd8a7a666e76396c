// The four kernels of the sphere crops (kernels/scene_crop.cl), each launched by itself on random
// point images and compared with a plain C++ reference of that one step
// (tests/support/kernel_refs.hpp). The predicate is bp_dist2 (kernels/scene_shared.h) on both
// sides and the kernels copy floats unchanged, so counts, pixels and copied points and normals
// compare exactly (bit for bit). The composed routines are tests/detect/scene/test_scene_prep.cpp's.
#include <gtest/gtest.h>

#include <random>
#include <tuple>

#include "host/detect/scene/scene_chunks.hpp"
#include "host/detect/scene/scene_crop.hpp"
#include "tests/support/kernel_refs.hpp"

using namespace binpick;
using namespace binpick::test;

namespace {

constexpr u32 kCanary = 0xdeadbeefu;
constexpr std::size_t kGuard = 8;
constexpr float kFloatCanary = -12345.0f;

// Normals for a point image: random unit vectors with w = 1, or all 0 (no normal) for about a
// fifth of the pixels and for every pixel without data.
std::vector<float> random_normals(std::mt19937& rng, const PointImage& pts) {
  std::normal_distribution<float> N(0.0f, 1.0f);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  std::vector<float> out(pts.xyzw.size(), 0.0f);
  for (std::size_t i = 0; i < out.size() / 4; ++i) {
    if (pts.xyzw[4 * i + 3] == 0.0f || U(rng) < 0.2f) continue;
    const Eigen::Vector3f n = Eigen::Vector3f(N(rng), N(rng), N(rng)).normalized();
    out[4 * i] = n.x(), out[4 * i + 1] = n.y(), out[4 * i + 2] = n.z(), out[4 * i + 3] = 1.0f;
  }
  return out;
}

// A sphere centre near a random pixel's point (the origin if it has none), on a grid of 1/8 mm
// so that put_on_sphere's point lies exactly on the sphere.
Eigen::Vector3f centre_near(std::mt19937& rng, const PointImage& pts) {
  std::uniform_int_distribution<std::size_t> pick(0, pts.xyzw.size() / 4 - 1);
  std::uniform_real_distribution<float> U(-30.0f, 30.0f);
  const float* p = &pts.xyzw[4 * pick(rng)];
  const Eigen::Vector3f c(p[0] + U(rng), p[1] + U(rng), p[2] + U(rng));
  return (c * 8.0f).array().round().matrix() / 8.0f;
}

// A point exactly on the sphere's surface, which the crop keeps ("<="): pixel i at
// centre + (3, 4, 0) s for a power of two s, radius 5 s: every difference and square is exact.
void put_on_sphere(PointImage& pts, std::size_t i, const Eigen::Vector3f& centre, float s) {
  pts.xyzw[4 * i] = centre.x() + 3 * s;
  pts.xyzw[4 * i + 1] = centre.y() + 4 * s;
  pts.xyzw[4 * i + 2] = centre.z();
  pts.xyzw[4 * i + 3] = 1.0f;
}

std::vector<float> float4s(std::size_t count) {
  return std::vector<float>(4 * count, kFloatCanary);
}

}  // namespace

TEST(CropKernels, crop_count_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("scene_crop.cl", "crop_count");
  std::mt19937 rng(501);
  for (auto [w, h, holes] : {std::tuple{1u, 1u, 0.0f}, {37u, 23u, 0.1f}, {160u, 120u, 0.05f},
                             {301u, 77u, 0.5f}}) {
    PointImage pts = random_point_image(rng, w, h, holes);
    const std::size_t n = std::size_t(w) * h;
    const std::vector<float> nrm = random_normals(rng, pts);
    ocl::Buffer<float> normals = upload(dev, nrm);
    for (int t = 0; t < 6; ++t) {
      const Eigen::Vector3f centre = centre_near(rng, pts);
      const float s = t == 0 ? 0.0f : std::ldexp(1.0f, t);  // radius 5 s, exact on the surface
      put_on_sphere(pts, n / 2, centre, s);
      ocl::Buffer<float> points = upload(dev, pts.xyzw);
      const float radius2 = 25 * s * s;
      // The routine's chunks (chunks_for), and chunks of 1 and of 97 pixels.
      const Chunks routine = chunks_for(n);
      for (const Chunks ch : {routine, Chunks{u32(n), 1u}, Chunks{u32((n + 96) / 97), 97u}})
        for (u32 require : {0u, 1u}) {
          ocl::Buffer<u32> counts = guarded_buffer(dev, std::vector<u32>(ch.count, kCanary), kGuard, kCanary);
          const cl_float4 c{{centre.x(), centre.y(), centre.z(), 0.0f}};
          ocl::launch(dev, k, ch.count, points, normals, u32(n), ch.size, c, radius2, require, counts);
          std::vector<u32> want = crop_count_reference(pts.xyzw, nrm, n, ch.size, ch.count, centre,
                                                       radius2, require != 0);
          want.insert(want.end(), kGuard, kCanary);
          ASSERT_EQ(counts.read(dev), want) << w << "x" << h << " t " << t << " chunk " << ch.size << " require " << require;
        }
      // The point on the sphere is kept (it has no normal unless random_normals gave it one).
      EXPECT_TRUE(crop_rect_keeps_reference(&pts.xyzw[4 * (n / 2)], centre, radius2));
    }
  }
}

TEST(CropKernels, crop_scatter_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("scene_crop.cl", "crop_scatter");
  std::mt19937 rng(502);
  for (auto [w, h, holes] : {std::tuple{1u, 1u, 0.0f}, {37u, 23u, 0.1f}, {160u, 120u, 0.05f},
                             {301u, 77u, 0.5f}}) {
    const PointImage pts = random_point_image(rng, w, h, holes);
    const std::size_t n = std::size_t(w) * h;
    const std::vector<float> nrm = random_normals(rng, pts);
    ocl::Buffer<float> points = upload(dev, pts.xyzw), normals = upload(dev, nrm);
    for (int t = 0; t < 5; ++t) {
      const Eigen::Vector3f centre = centre_near(rng, pts);
      const float radius2 = t == 0 ? 0.0f : t == 1 ? 1e12f : float(std::pow(40.0f * t, 2));
      const cl_float4 c{{centre.x(), centre.y(), centre.z(), 0.0f}};
      for (const Chunks ch : {chunks_for(n), Chunks{u32((n + 96) / 97), 97u}})
        for (bool require : {false, true}) {
          // Offsets from the reference counts (the host's scan in the routine).
          u32 total = 0;
          const std::vector<u32> offsets = exclusive_offsets(
              crop_count_reference(pts.xyzw, nrm, n, ch.size, ch.count, centre, radius2, require), &total);
          ocl::Buffer<u32> offs = upload(dev, offsets);
          std::vector<float> want_p = float4s(total + kGuard), want_n = float4s(total + kGuard);
          ocl::Buffer<float> out_p = upload(dev, want_p), out_n = upload(dev, want_n);
          ocl::launch(dev, k, ch.count, points, normals, u32(n), ch.size, c, radius2, u32(require),
                      offs, out_p, out_n);
          crop_scatter_reference(pts.xyzw, nrm, n, ch.size, ch.count, centre, radius2, require,
                                 offsets, want_p, want_n);
          const std::vector<float> got_p = out_p.read(dev), got_n = out_n.read(dev);
          for (std::size_t i = 0; i < want_p.size(); ++i) {
            ASSERT_TRUE(same_bits(got_p[i], want_p[i])) << "point float " << i << " of " << total;
            ASSERT_TRUE(same_bits(got_n[i], want_n[i])) << "normal float " << i << " of " << total;
          }
        }
    }
  }
}

TEST(CropKernels, crop_rect_count_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("scene_crop.cl", "crop_rect_count");
  std::mt19937 rng(503);
  for (auto [w, h, holes] : {std::tuple{1u, 1u, 0.0f}, {37u, 23u, 0.1f}, {160u, 120u, 0.05f},
                             {301u, 77u, 0.5f}}) {
    PointImage pts = random_point_image(rng, w, h, holes);
    std::uniform_int_distribution<u32> X(0, w), Y(0, h);
    for (int t = 0; t < 8; ++t) {
      const Eigen::Vector3f centre = centre_near(rng, pts);
      const float s = t == 0 ? 0.0f : std::ldexp(1.0f, t);
      put_on_sphere(pts, (std::size_t(h) / 2) * w + w / 2, centre, s);
      ocl::Buffer<float> points = upload(dev, pts.xyzw);
      // The whole image, a single row, a single column, and random rectangles (row counts that
      // are not multiples of the work group of 8).
      std::array<u32, 4> rect{0, 0, w, h};
      if (t == 1) rect = {0, h / 2, w, h / 2 + 1};
      if (t == 2) rect = {w / 2, 0, w / 2 + 1, h};
      if (t >= 3) {
        u32 x0 = X(rng), x1 = X(rng), y0 = Y(rng), y1 = Y(rng);
        rect = {std::min(x0, x1), std::min(y0, y1), std::max(x0, x1), std::max(y0, y1)};
      }
      const u32 rows = rect[3] - rect[1];
      const float radius2 = 25 * s * s;
      const cl_float4 c{{centre.x(), centre.y(), centre.z(), 0.0f}};
      const cl_uint4 r{{rect[0], rect[1], rect[2], rect[3]}};
      ocl::Buffer<u32> counts = guarded_buffer(dev, std::vector<u32>(rows, kCanary), kGuard, kCanary);
      ocl::launch_local(dev, k, rows, 8, points, w, r, c, radius2, counts);  // as the routine
      std::vector<u32> want = crop_rect_count_reference(pts.xyzw, w, rect, centre, radius2);
      want.insert(want.end(), kGuard, kCanary);
      ASSERT_EQ(counts.read(dev), want) << w << "x" << h << " t " << t;
    }
  }
}

TEST(CropKernels, crop_rect_scatter_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("scene_crop.cl", "crop_rect_scatter");
  std::mt19937 rng(504);
  for (auto [w, h, holes] : {std::tuple{1u, 1u, 0.0f}, {37u, 23u, 0.1f}, {160u, 120u, 0.05f},
                             {301u, 77u, 0.5f}}) {
    const PointImage pts = random_point_image(rng, w, h, holes);
    ocl::Buffer<float> points = upload(dev, pts.xyzw);
    const bp_camera cam{150.0f, 150.0f, (w - 1) / 2.0f, (h - 1) / 2.0f, 0.1f, w, h, 0};
    std::uniform_int_distribution<u32> X(0, w), Y(0, h);
    for (int t = 0; t < 8; ++t) {
      const Eigen::Vector3f centre = centre_near(rng, pts);
      const float radius = t == 0 ? 0.0f : 20.0f * t;
      // The routine's rectangle (crop_pixel_rect), or a random one.
      std::array<u32, 4> rect = crop_pixel_rect(cam, {centre, radius, false});
      if (t % 2) {
        u32 x0 = X(rng), x1 = X(rng), y0 = Y(rng), y1 = Y(rng);
        rect = {std::min(x0, x1), std::min(y0, y1), std::max(x0, x1), std::max(y0, y1)};
      }
      const u32 rows = rect[3] - rect[1];
      const float radius2 = radius * radius;
      u32 total = 0;
      const std::vector<u32> offsets =
          exclusive_offsets(crop_rect_count_reference(pts.xyzw, w, rect, centre, radius2), &total);
      ocl::Buffer<u32> offs = upload(dev, offsets);
      std::vector<u32> want_pixels(total + kGuard, kCanary);
      std::vector<float> want_points = float4s(total + kGuard);
      ocl::Buffer<u32> out_pixels = upload(dev, want_pixels);
      ocl::Buffer<float> out_points = upload(dev, want_points);
      const cl_float4 c{{centre.x(), centre.y(), centre.z(), 0.0f}};
      const cl_uint4 r{{rect[0], rect[1], rect[2], rect[3]}};
      ocl::launch_local(dev, k, rows, 8, points, w, r, c, radius2, offs, out_pixels, out_points);
      crop_rect_scatter_reference(pts.xyzw, w, rect, centre, radius2, offsets, want_pixels, want_points);
      ASSERT_EQ(out_pixels.read(dev), want_pixels) << w << "x" << h << " t " << t;
      const std::vector<float> got_points = out_points.read(dev);
      for (std::size_t i = 0; i < want_points.size(); ++i)
        ASSERT_TRUE(same_bits(got_points[i], want_points[i])) << i;
    }
  }
}

// Degenerate images: all pixels without data (nothing counted or written), one pixel, a radius
// of 0 around a point (kept: distance 0 <= 0), an empty rectangle; and the routine's sequence
// count -> host scan -> scatter gives crop_sphere_reference / crop_pixels_reference.
TEST(CropKernels, DegenerateImagesAndTheRoutineSequence) {
  auto& dev = ocl::Device::shared();
  cl::Kernel count = dev.kernel("scene_crop.cl", "crop_count");
  cl::Kernel scatter = dev.kernel("scene_crop.cl", "crop_scatter");
  cl::Kernel rcount = dev.kernel("scene_crop.cl", "crop_rect_count");
  cl::Kernel rscatter = dev.kernel("scene_crop.cl", "crop_rect_scatter");
  std::mt19937 rng(505);
  std::vector<PointImage> images;
  images.push_back(PointImage{13, 7, std::vector<float>(4 * 13 * 7, 0.0f)});  // all invalid
  images.push_back(random_point_image(rng, 1, 1, 0.0f));
  images.push_back(random_point_image(rng, 50, 3, 0.3f));
  for (const PointImage& pts : images) {
    const std::size_t n = std::size_t(pts.width) * pts.height;
    std::vector<float> nrm(pts.xyzw.size(), 0.0f);
    for (std::size_t i = 0; i < n; ++i) nrm[4 * i + 2] = -1.0f, nrm[4 * i + 3] = pts.xyzw[4 * i + 3];
    ocl::Buffer<float> points = upload(dev, pts.xyzw), normals = upload(dev, nrm);
    // Centred on the last valid point (or the origin) with radius 0, then a large radius.
    Eigen::Vector3f centre = Eigen::Vector3f::Zero();
    for (std::size_t i = 0; i < n; ++i)
      if (pts.xyzw[4 * i + 3] != 0) centre = Eigen::Vector3f(pts.xyzw[4 * i], pts.xyzw[4 * i + 1], pts.xyzw[4 * i + 2]);
    for (float radius : {0.0f, 500.0f}) {
      const CropOptions opt{centre, radius, true};
      const float radius2 = radius * radius;
      const cl_float4 c{{centre.x(), centre.y(), centre.z(), 0.0f}};
      // crop_sphere's sequence, launched in padded work groups of 16.
      const Chunks ch = chunks_for(n);
      ocl::Buffer<u32> counts = guarded_buffer(dev, std::vector<u32>(ch.count, kCanary), kGuard, kCanary);
      ocl::launch_local(dev, count, ch.count, 16, points, normals, u32(n), ch.size, c, radius2, 1u, counts);
      std::vector<u32> got_counts = counts.read(dev);
      const std::vector<u32> want_counts = crop_count_reference(pts.xyzw, nrm, n, ch.size, ch.count, centre, radius2, true);
      ASSERT_EQ(std::vector<u32>(got_counts.begin(), got_counts.begin() + ch.count), want_counts);
      for (std::size_t i = ch.count; i < got_counts.size(); ++i) ASSERT_EQ(got_counts[i], kCanary);
      u32 total = 0;
      ocl::Buffer<u32> offs = upload(dev, exclusive_offsets(want_counts, &total));
      ocl::Buffer<float> out_p = upload(dev, float4s(total + kGuard)), out_n = upload(dev, float4s(total + kGuard));
      ocl::launch_local(dev, scatter, ch.count, 16, points, normals, u32(n), ch.size, c, radius2, 1u,
                        offs, out_p, out_n);
      const PointCloud want = crop_sphere_reference(pts, PointImage{pts.width, pts.height, nrm}, opt);
      ASSERT_EQ(total, want.points.size());
      const std::vector<float> got_p = out_p.read(dev), got_n = out_n.read(dev);
      for (std::size_t i = 0; i < total; ++i)
        for (int a = 0; a < 3; ++a) {
          ASSERT_EQ(got_p[4 * i + a], want.points[i][a]);
          ASSERT_EQ(got_n[4 * i + a], want.normals[i][a]);
        }
      for (std::size_t i = 4 * total; i < got_p.size(); ++i) ASSERT_EQ(got_p[i], kFloatCanary);
      if (&pts == &images[0]) {
        EXPECT_EQ(total, 0u);  // no pixel has data
      } else if (radius == 0) {
        EXPECT_EQ(total, 1u);  // the centre point only
      }

      // crop_pixels' sequence over the whole image and over an empty rectangle.
      for (const std::array<u32, 4> rect : {std::array<u32, 4>{0, 0, pts.width, pts.height},
                                            std::array<u32, 4>{0, 1, 0, 1}}) {
        const u32 rows = rect[3] - rect[1];
        const cl_uint4 r{{rect[0], rect[1], rect[2], rect[3]}};
        ocl::Buffer<u32> rc = guarded_buffer(dev, std::vector<u32>(rows, kCanary), kGuard, kCanary);
        ocl::launch_local(dev, rcount, rows, 8, points, pts.width, r, c, radius2, rc);
        const std::vector<u32> want_rc = crop_rect_count_reference(pts.xyzw, pts.width, rect, centre, radius2);
        const std::vector<u32> got_rc = rc.read(dev);
        ASSERT_EQ(std::vector<u32>(got_rc.begin(), got_rc.begin() + rows), want_rc);
        u32 rtotal = 0;
        ocl::Buffer<u32> roffs = upload(dev, exclusive_offsets(want_rc, &rtotal));
        ocl::Buffer<u32> pixels = guarded_buffer(dev, std::vector<u32>(rtotal, kCanary), kGuard, kCanary);
        ocl::Buffer<float> rpoints = upload(dev, float4s(rtotal + kGuard));
        ocl::launch_local(dev, rscatter, rows, 8, points, pts.width, r, c, radius2, roffs, pixels, rpoints);
        const CroppedPixels want_px = crop_pixels_reference(pts, opt);
        const std::vector<u32> got_px = pixels.read(dev);
        if (rows == 0 || rect[2] == rect[0]) {
          EXPECT_EQ(rtotal, 0u);
        } else {
          ASSERT_EQ(std::vector<u32>(got_px.begin(), got_px.begin() + rtotal), want_px.pixels);
        }
        for (std::size_t i = rtotal; i < got_px.size(); ++i) ASSERT_EQ(got_px[i], kCanary);
      }
    }
  }
}
