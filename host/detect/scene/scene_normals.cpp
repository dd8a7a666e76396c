#include "host/detect/scene/scene_normals.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Eigenvalues>

#include "host/core/error.hpp"
#include "kernels/scene_shared.h"

namespace binpick {

void check_point_image(const PointImage& points) {
  if (points.xyzw.size() != 4 * std::size_t(points.width) * points.height)
    throw InputError("point image of " + std::to_string(points.width) + " x " +
                     std::to_string(points.height) + " holds " +
                     std::to_string(points.xyzw.size()) + " floats, not 4 a pixel");
  if (std::size_t(points.width) * points.height >= BP_NO_PIXEL)
    throw InputError("point image too large for 32-bit pixel indices");
}

void check(const NormalOptions& opt) {
  if (opt.radius < 0 || opt.radius > 32)
    throw InputError("normal window radius must be in [0, 32] pixels, not " +
                     std::to_string(opt.radius));
  if (!(opt.max_distance > 0))
    throw InputError("normal neighbour distance must be positive (mm)");
  if (!(opt.metric_radius >= 0) || std::isinf(opt.metric_radius))
    throw InputError("normal radius must be finite and >= 0 (mm)");
  if (opt.metric_radius > 0 && !(opt.focal > 0 && std::isfinite(opt.focal)))
    throw InputError("a metric normal radius needs the camera's focal length");
}

namespace {

// The kernel of a window: radii 1 to 3 have kernels with the radius a compile-time constant
// (vectorised: faster); metric windows and other radii take the generic one.
std::string normals_kernel(const std::string& base, const NormalOptions& opt) {
  return opt.metric_radius == 0 && opt.radius >= 1 && opt.radius <= 3
             ? base + "_r" + std::to_string(opt.radius)
             : base;
}

}  // namespace

void enqueue_normals_from_points(ocl::Device& dev, const ocl::Buffer<float>& points,
                                 std::uint32_t width, std::uint32_t height,
                                 const NormalOptions& opt, ocl::Buffer<float>& normals) {
  cl::Kernel k = dev.kernel("scene_normals.cl", normals_kernel("normals_from_points", opt));
  ocl::launch(dev, k, std::size_t(width) * height, points, cl_uint(width), cl_uint(height),
              cl_int(opt.radius), opt.max_distance, opt.metric_radius, opt.focal, normals);
}

PointImage normals_from_points(ocl::Device& dev, const PointImage& points,
                               const NormalOptions& opt) {
  check_point_image(points);
  check(opt);
  const std::size_t n = std::size_t(points.width) * points.height;
  ocl::Buffer<float> in(dev, std::span<const float>(points.xyzw), CL_MEM_READ_ONLY);
  ocl::Buffer<float> out(dev, 4 * n, CL_MEM_WRITE_ONLY);
  enqueue_normals_from_points(dev, in, points.width, points.height, opt, out);
  return {points.width, points.height, out.read(dev)};
}

namespace {

// The reference normal of pixel (u, v) into o[0..3] (left untouched when there is none).
void reference_normal_at(const PointImage& points, const NormalOptions& opt, int u, int v,
                         float* o) {
  const int w = int(points.width), h = int(points.height);
  auto at = [&](int x, int y) { return &points.xyzw[4 * (std::size_t(y) * w + x)]; };
  const float* c = at(u, v);
  if (c[3] == 0.0f) return;
  int radius = opt.radius, step = 1;
  float max_distance = opt.max_distance;
  if (opt.metric_radius > 0) {
    bp_metric_window(c[2], opt.metric_radius, opt.focal, &radius, &step);
    max_distance = std::min(max_distance, opt.metric_radius);
  }
  const float max2 = max_distance * max_distance;
  int n = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sq = Eigen::Matrix3d::Zero();
  for (int y = v - radius; y <= v + radius; y += step)
    for (int x = u - radius; x <= u + radius; x += step) {
      if (x < 0 || y < 0 || x >= w || y >= h) continue;
      const float* p = at(x, y);
      // The same float predicate as the kernel, so both use the same neighbours.
      if (p[3] == 0.0f || bp_dist2(p[0], p[1], p[2], c[0], c[1], c[2]) > max2) continue;
      const Eigen::Vector3d q(double(p[0]) - c[0], double(p[1]) - c[1], double(p[2]) - c[2]);
      ++n;
      sum += q;
      sq += q * q.transpose();
    }
  if (n < 3) return;
  const Eigen::Vector3d mean = sum / n;
  const Eigen::Matrix3d cov = sq / n - mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);  // eigenvalues ascending
  const Eigen::Vector3d ev = es.eigenvalues();
  if (!(ev[1] > double(BP_NORMAL_DEGENERATE_RATIO) * ev[2])) return;
  Eigen::Vector3d nrm = es.eigenvectors().col(0).normalized();
  if (nrm.dot(Eigen::Vector3d(c[0], c[1], c[2])) > 0) nrm = -nrm;
  o[0] = float(nrm[0]), o[1] = float(nrm[1]), o[2] = float(nrm[2]), o[3] = 1.0f;
}

void check_pixels(std::uint32_t width, std::uint32_t height,
                  const std::vector<std::uint32_t>& pixels) {
  const std::size_t n = std::size_t(width) * height;
  for (std::uint32_t p : pixels)
    if (p >= n)
      throw InputError("pixel " + std::to_string(p) + " outside an image of " +
                       std::to_string(width) + " x " + std::to_string(height));
}

}  // namespace

PointImage normals_from_points_reference(const PointImage& points, const NormalOptions& opt) {
  check_point_image(points);
  check(opt);
  PointImage out{points.width, points.height, std::vector<float>(points.xyzw.size(), 0.0f)};
  for (int v = 0; v < int(points.height); ++v)
    for (int u = 0; u < int(points.width); ++u)
      reference_normal_at(points, opt, u, v, &out.xyzw[4 * (std::size_t(v) * points.width + u)]);
  return out;
}

std::vector<float> normals_at_pixels(ocl::Device& dev, const ocl::Buffer<float>& points,
                                     std::uint32_t width, std::uint32_t height,
                                     const std::vector<std::uint32_t>& pixels,
                                     const NormalOptions& opt) {
  check(opt);
  check_pixels(width, height, pixels);
  if (pixels.empty()) return {};
  cl::Kernel k = dev.kernel("scene_normals.cl", normals_kernel("normals_at_pixels", opt));
  ocl::Buffer<std::uint32_t> list(dev, std::span<const std::uint32_t>(pixels), CL_MEM_READ_ONLY);
  ocl::Buffer<float> out(dev, 4 * pixels.size(), CL_MEM_WRITE_ONLY);
  // Fixed work groups: list lengths change every call (see ocl::launch_local).
  ocl::launch_local(dev, k, pixels.size(), 32, points, cl_uint(width), cl_uint(height),
                    cl_int(opt.radius), opt.max_distance, opt.metric_radius, opt.focal, list,
                    cl_uint(pixels.size()), out);
  return out.read(dev);
}

std::vector<float> normals_at_pixels(ocl::Device& dev, const PointImage& points,
                                     const std::vector<std::uint32_t>& pixels,
                                     const NormalOptions& opt) {
  check_point_image(points);
  ocl::Buffer<float> in(dev, std::span<const float>(points.xyzw), CL_MEM_READ_ONLY);
  return normals_at_pixels(dev, in, points.width, points.height, pixels, opt);
}

std::vector<float> normals_at_pixels_reference(const PointImage& points,
                                               const std::vector<std::uint32_t>& pixels,
                                               const NormalOptions& opt) {
  check_point_image(points);
  check(opt);
  check_pixels(points.width, points.height, pixels);
  std::vector<float> out(4 * pixels.size(), 0.0f);
  for (std::size_t j = 0; j < pixels.size(); ++j)
    reference_normal_at(points, opt, int(pixels[j] % points.width), int(pixels[j] / points.width),
                        &out[4 * j]);
  return out;
}

}  // namespace binpick
