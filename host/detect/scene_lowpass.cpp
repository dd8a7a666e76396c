#include "host/detect/scene_lowpass.hpp"

#include <algorithm>
#include <string>

#include "host/core/error.hpp"
#include "host/detect/scene_normals.hpp"

namespace binpick {

void check_lowpass_radius(int radius) {
  if (radius < 0 || radius > 64)
    throw InputError("low-pass radius must be in [0, 64] pixels, not " + std::to_string(radius));
}

void enqueue_lowpass_depth(ocl::Device& dev, const ocl::Buffer<float>& points,
                           std::uint32_t width, std::uint32_t height, int radius,
                           ocl::Buffer<float>& row_sums, ocl::Buffer<float>& filtered) {
  const std::size_t n = std::size_t(width) * height;
  cl::Kernel rows = dev.kernel("scene_lowpass.cl", "lowpass_rows");
  cl::Kernel cols = dev.kernel("scene_lowpass.cl", "lowpass_cols");
  ocl::launch(dev, rows, n, points, cl_uint(width), cl_uint(height), cl_int(radius), row_sums);
  ocl::launch(dev, cols, n, points, row_sums, cl_uint(width), cl_uint(height), cl_int(radius),
              filtered);
}

std::vector<float> lowpass_depth(ocl::Device& dev, const PointImage& points, int radius) {
  check_point_image(points);
  check_lowpass_radius(radius);
  const std::size_t n = std::size_t(points.width) * points.height;
  ocl::Buffer<float> in(dev, std::span<const float>(points.xyzw), CL_MEM_READ_ONLY);
  ocl::Buffer<float> row_sums(dev, 2 * n), out(dev, n, CL_MEM_WRITE_ONLY);
  enqueue_lowpass_depth(dev, in, points.width, points.height, radius, row_sums, out);
  return out.read(dev);
}

std::vector<float> lowpass_depth_reference(const PointImage& points, int radius) {
  check_point_image(points);
  check_lowpass_radius(radius);
  const int w = int(points.width), h = int(points.height);
  const std::size_t n = std::size_t(w) * h;
  auto valid = [&](std::size_t i) { return points.xyzw[4 * i + 3] != 0.0f; };
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
