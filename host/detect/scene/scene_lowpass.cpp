#include "host/detect/scene/scene_lowpass.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "host/core/error.hpp"
#include "host/detect/scene/scene_normals.hpp"

namespace binpick {

void check_lowpass_radius(int radius) {
  if (radius < 0 || radius > 64)
    throw InputError("low-pass radius must be in [0, 64] pixels, not " + std::to_string(radius));
}

std::size_t lowpass_work_items(std::uint32_t width, std::uint32_t height) {
  return std::size_t((width + kLowpassBlock - 1) / kLowpassBlock) * height;
}

void enqueue_lowpass_depth(ocl::Device& dev, const ocl::Buffer<float>& points,
                           std::uint32_t width, std::uint32_t height, int radius,
                           ocl::Buffer<float>& filtered, const ocl::Buffer<std::uint8_t>* mask) {
  const std::size_t n = std::size_t(width) * height;
  if (points.size() < 4 * n || filtered.size() < n || (mask && mask->size() < n))
    throw std::logic_error("enqueue_lowpass_depth: a buffer is smaller than the image");
  if (n == 0) return;
  // Scratch of the passes; released here, kept by the queue until its kernels are done.
  ocl::Buffer<float> pairs(dev, 2 * n), row_sums(dev, 2 * n);
  if (mask) {
    cl::Kernel k = dev.kernel("scene_lowpass.cl", "lowpass_pairs_masked");
    ocl::launch(dev, k, n, points, *mask, cl_uint(n), pairs);
  } else {
    cl::Kernel k = dev.kernel("scene_lowpass.cl", "lowpass_pairs");
    ocl::launch(dev, k, n, points, cl_uint(n), pairs);
  }
  cl::Kernel rows = dev.kernel("scene_lowpass.cl", "lowpass_rows");
  cl::Kernel cols = dev.kernel("scene_lowpass.cl", "lowpass_cols");
  const std::size_t blocks = lowpass_work_items(width, height);
  ocl::launch(dev, rows, blocks, pairs, cl_uint(width), cl_uint(height), cl_int(radius), row_sums);
  ocl::launch(dev, cols, blocks, pairs, row_sums, cl_uint(width), cl_uint(height), cl_int(radius),
              filtered);
}

void enqueue_lowpass_points(ocl::Device& dev, const ocl::Buffer<float>& points,
                            const ocl::Buffer<float>& filtered, std::size_t n,
                            ocl::Buffer<float>& out) {
  if (points.size() < 4 * n || filtered.size() < n || out.size() < 4 * n)
    throw std::logic_error("enqueue_lowpass_points: a buffer is smaller than the image");
  if (n == 0) return;
  cl::Kernel k = dev.kernel("scene_lowpass.cl", "lowpass_points");
  ocl::launch(dev, k, n, points, filtered, cl_uint(n), out);
}

std::vector<float> lowpass_points_reference(const std::vector<float>& xyzw,
                                            const std::vector<float>& filtered) {
  if (xyzw.size() != 4 * filtered.size())
    throw InputError("lowpass_points: one low-passed depth a point expected");
  std::vector<float> out = xyzw;
  for (std::size_t i = 0; i < filtered.size(); ++i) {
    const float* p = &xyzw[4 * i];
    if (!(p[3] != 0.0f && filtered[i] > 0.0f)) continue;
    const float s = filtered[i] / p[2];
    out[4 * i] = p[0] * s, out[4 * i + 1] = p[1] * s, out[4 * i + 2] = p[2] * s;
    out[4 * i + 3] = 1.0f;
  }
  return out;
}

namespace {

void check_mask(const PointImage& points, const std::vector<std::uint8_t>* mask) {
  if (mask && mask->size() != std::size_t(points.width) * points.height)
    throw InputError("the low-pass mask has " + std::to_string(mask->size()) +
                     " bytes for an image of " + std::to_string(points.width) + " x " +
                     std::to_string(points.height));
}

}  // namespace

std::vector<float> lowpass_depth(ocl::Device& dev, const PointImage& points, int radius,
                                 const std::vector<std::uint8_t>* mask) {
  check_point_image(points);
  check_lowpass_radius(radius);
  check_mask(points, mask);
  const std::size_t n = std::size_t(points.width) * points.height;
  if (n == 0) return {};
  ocl::Buffer<float> in(dev, std::span<const float>(points.xyzw), CL_MEM_READ_ONLY);
  ocl::Buffer<float> out(dev, n, CL_MEM_WRITE_ONLY);
  if (!mask) {
    enqueue_lowpass_depth(dev, in, points.width, points.height, radius, out);
    return out.read(dev);
  }
  const ocl::Buffer<std::uint8_t> m(dev, std::span<const std::uint8_t>(*mask), CL_MEM_READ_ONLY);
  enqueue_lowpass_depth(dev, in, points.width, points.height, radius, out, &m);
  return out.read(dev);
}

std::vector<float> lowpass_depth_reference(const PointImage& points, int radius,
                                           const std::vector<std::uint8_t>* mask) {
  check_point_image(points);
  check_lowpass_radius(radius);
  check_mask(points, mask);
  const int w = int(points.width), h = int(points.height);
  const std::size_t n = std::size_t(w) * h;
  auto valid = [&](std::size_t i) {
    return points.xyzw[4 * i + 3] != 0.0f && (!mask || (*mask)[i] != 0);
  };
  std::vector<float> sum(n), count(n), out(n, 0.0f);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      float s = 0.0f, c = 0.0f;
      for (int x = std::max(u - radius, 0); x <= std::min(u + radius, w - 1); ++x) {
        const std::size_t j = std::size_t(v) * w + x;
        if (!valid(j)) continue;
        s += points.xyzw[4 * j + 2];
        c += 1.0f;
      }
      sum[std::size_t(v) * w + u] = s, count[std::size_t(v) * w + u] = c;
    }
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const std::size_t i = std::size_t(v) * w + u;
      if (!valid(i)) continue;
      float s = 0.0f, c = 0.0f;
      for (int y = std::max(v - radius, 0); y <= std::min(v + radius, h - 1); ++y) {
        s += sum[std::size_t(y) * w + u];
        c += count[std::size_t(y) * w + u];
      }
      out[i] = s / c;
    }
  return out;
}

}  // namespace binpick
