#include "host/detect/scene/scene_crop.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "host/core/error.hpp"
#include "host/detect/scene/scene_chunks.hpp"
#include "host/detect/scene/scene_normals.hpp"
#include "kernels/scene_shared.h"

namespace binpick {
namespace {

void check(const CropOptions& opt) {
  if (!opt.centre.allFinite()) throw InputError("crop centre must be finite");
  if (!(opt.radius >= 0) || std::isinf(opt.radius))
    throw InputError("crop radius must be finite and non-negative (mm)");
}

void check(const PointImage& points, const PointImage& normals) {
  check_point_image(points);
  check_point_image(normals);
  if (points.width != normals.width || points.height != normals.height)
    throw InputError("normal image does not match the point image");
}

}  // namespace

PointCloud crop_sphere(ocl::Device& dev, const ocl::Buffer<float>& points,
                       const ocl::Buffer<float>& normals, std::size_t n, const CropOptions& opt) {
  check(opt);
  const Chunks ch = chunks_for(n);
  if (ch.count == 0) return {};
  const cl_float4 centre{{opt.centre.x(), opt.centre.y(), opt.centre.z(), 0.0f}};
  const float radius2 = opt.radius * opt.radius;
  const cl_uint need_normal = opt.require_normals ? 1 : 0;
  ocl::Buffer<cl_uint> counts(dev, ch.count);
  cl::Kernel count = dev.kernel("scene_crop.cl", "crop_count");
  ocl::launch(dev, count, ch.count, points, normals, cl_uint(n), cl_uint(ch.size), centre,
              radius2, need_normal, counts);
  // Exclusive scan of a few hundred counts: cheaper on the host than another launch.
  std::vector<cl_uint> offsets = counts.read(dev);
  cl_uint total = 0;
  for (cl_uint& c : offsets) {
    const cl_uint here = c;
    c = total;
    total += here;
  }
  if (total == 0) return {};
  ocl::Buffer<cl_uint> offs(dev, std::span<const cl_uint>(offsets), CL_MEM_READ_ONLY);
  ocl::Buffer<float> out_p(dev, 4 * std::size_t(total)), out_n(dev, 4 * std::size_t(total));
  cl::Kernel scatter = dev.kernel("scene_crop.cl", "crop_scatter");
  ocl::launch(dev, scatter, ch.count, points, normals, cl_uint(n), cl_uint(ch.size), centre,
              radius2, need_normal, offs, out_p, out_n);
  const std::vector<float> p = out_p.read(dev), nr = out_n.read(dev);
  PointCloud cloud;
  cloud.points.reserve(total);
  cloud.normals.reserve(total);
  for (std::size_t i = 0; i < total; ++i) {
    cloud.points.emplace_back(p[4 * i], p[4 * i + 1], p[4 * i + 2]);
    cloud.normals.emplace_back(nr[4 * i], nr[4 * i + 1], nr[4 * i + 2]);
  }
  return cloud;
}

PointCloud crop_sphere(ocl::Device& dev, const PointImage& points, const PointImage& normals,
                       const CropOptions& opt) {
  check(points, normals);
  check(opt);
  ocl::Buffer<float> p(dev, std::span<const float>(points.xyzw), CL_MEM_READ_ONLY);
  ocl::Buffer<float> nr(dev, std::span<const float>(normals.xyzw), CL_MEM_READ_ONLY);
  return crop_sphere(dev, p, nr, std::size_t(points.width) * points.height, opt);
}

PointCloud crop_sphere_reference(const PointImage& points, const PointImage& normals,
                                 const CropOptions& opt) {
  check(points, normals);
  check(opt);
  const float radius2 = opt.radius * opt.radius;
  PointCloud cloud;
  for (std::size_t i = 0; i < std::size_t(points.width) * points.height; ++i) {
    const float* p = &points.xyzw[4 * i];
    const float* nr = &normals.xyzw[4 * i];
    if (p[3] == 0.0f || (opt.require_normals && nr[3] == 0.0f)) continue;
    if (!(bp_dist2(p[0], p[1], p[2], opt.centre.x(), opt.centre.y(), opt.centre.z()) <= radius2))
      continue;
    cloud.points.emplace_back(p[0], p[1], p[2]);
    cloud.normals.emplace_back(nr[0], nr[1], nr[2]);
  }
  return cloud;
}

std::array<std::uint32_t, 4> crop_pixel_rect(const bp_camera& cam, const CropOptions& opt) {
  check(opt);
  const std::array<std::uint32_t, 4> whole{0, 0, cam.width, cam.height};
  // Grown far beyond the float rounding of the points and of the distance test (~1e-7
  // relative), so no pixel that the exact predicate keeps can fall outside.
  const double r = double(opt.radius) * (1 + 1e-4) + 1e-3;
  const double x = opt.centre.x(), y = opt.centre.y(), z = opt.centre.z();
  if (!(z - r > 1e-3 * r + 1e-3) || !(cam.fx > 0) || !(cam.fy > 0)) return whole;
  // A point of the sphere has x in [x - r, x + r] and z in [z - r, z + r] (z > 0), so its
  // ray slope x / z lies between the slopes of the box's corners (monotone in each).
  auto span = [&](double c, double f, double pc, std::uint32_t size) {
    double lo = INFINITY, hi = -INFINITY;
    for (double a : {c - r, c + r})
      for (double b : {z - r, z + r}) lo = std::min(lo, a / b), hi = std::max(hi, a / b);
    const double p0 = std::floor(pc + f * lo) - 2, p1 = std::ceil(pc + f * hi) + 3;
    const auto clampu = [&](double p) {
      return std::uint32_t(std::clamp(p, 0.0, double(size)));
    };
    return std::pair(clampu(p0), clampu(p1));
  };
  const auto [x0, x1] = span(x, cam.fx, cam.cx, cam.width);
  const auto [y0, y1] = span(y, cam.fy, cam.cy, cam.height);
  return {x0, y0, x1, y1};
}

CroppedPixels crop_pixels(ocl::Device& dev, const ocl::Buffer<float>& points,
                          const bp_camera& cam, const CropOptions& opt,
                          const ocl::Buffer<std::uint8_t>* mask) {
  const std::array<std::uint32_t, 4> rect = crop_pixel_rect(cam, opt);
  if (mask && mask->size() != std::size_t(cam.width) * cam.height)
    throw InputError("the crop mask does not match the camera's image");
  CroppedPixels out;
  if (rect[2] <= rect[0] || rect[3] <= rect[1]) return out;
  const std::uint32_t rows = rect[3] - rect[1];
  const cl_uint4 r{{rect[0], rect[1], rect[2], rect[3]}};
  const cl_float4 centre{{opt.centre.x(), opt.centre.y(), opt.centre.z(), 0.0f}};
  const float radius2 = opt.radius * opt.radius;
  ocl::Buffer<cl_uint> counts(dev, rows);
  // Fixed work groups: the number of rows changes with every sphere (see ocl::launch_local).
  if (mask) {
    cl::Kernel count = dev.kernel("scene_crop.cl", "crop_rect_count_masked");
    ocl::launch_local(dev, count, rows, 8, points, *mask, cl_uint(cam.width), r, centre, radius2,
                      counts);
  } else {
    cl::Kernel count = dev.kernel("scene_crop.cl", "crop_rect_count");
    ocl::launch_local(dev, count, rows, 8, points, cl_uint(cam.width), r, centre, radius2, counts);
  }
  std::vector<cl_uint> offsets = counts.read(dev);
  cl_uint total = 0;
  for (cl_uint& c : offsets) {
    const cl_uint here = c;
    c = total;
    total += here;
  }
  if (total == 0) return out;
  ocl::Buffer<cl_uint> offs(dev, std::span<const cl_uint>(offsets), CL_MEM_READ_ONLY);
  ocl::Buffer<cl_uint> out_pixels(dev, total);
  ocl::Buffer<float> out_points(dev, 4 * std::size_t(total));
  if (mask) {
    cl::Kernel scatter = dev.kernel("scene_crop.cl", "crop_rect_scatter_masked");
    ocl::launch_local(dev, scatter, rows, 8, points, *mask, cl_uint(cam.width), r, centre,
                      radius2, offs, out_pixels, out_points);
  } else {
    cl::Kernel scatter = dev.kernel("scene_crop.cl", "crop_rect_scatter");
    ocl::launch_local(dev, scatter, rows, 8, points, cl_uint(cam.width), r, centre, radius2, offs,
                      out_pixels, out_points);
  }
  out.pixels = out_pixels.read(dev);
  const std::vector<float> p = out_points.read(dev);
  out.points.reserve(total);
  for (std::size_t i = 0; i < total; ++i) out.points.emplace_back(p[4 * i], p[4 * i + 1], p[4 * i + 2]);
  return out;
}

CroppedPixels crop_pixels_reference(const PointImage& points, const CropOptions& opt,
                                    const std::vector<std::uint8_t>* mask) {
  check_point_image(points);
  check(opt);
  if (mask && mask->size() != std::size_t(points.width) * points.height)
    throw InputError("the crop mask does not match the point image");
  const float radius2 = opt.radius * opt.radius;
  CroppedPixels out;
  for (std::size_t i = 0; i < std::size_t(points.width) * points.height; ++i) {
    const float* p = &points.xyzw[4 * i];
    if ((mask && !(*mask)[i]) || p[3] == 0.0f ||
        !(bp_dist2(p[0], p[1], p[2], opt.centre.x(), opt.centre.y(), opt.centre.z()) <= radius2))
      continue;
    out.pixels.push_back(std::uint32_t(i));
    out.points.emplace_back(p[0], p[1], p[2]);
  }
  return out;
}

PointCloud crop_sphere(const PreparedScene& scene, const CropOptions& opt) {
  if (!scene.has_normals)
    throw InputError("the prepared scene has no normals (ScenePrepOptions::normals_everywhere)");
  if (scene.device)
    return crop_sphere(*scene.device->dev, scene.device->points, scene.device->normals,
                       std::size_t(scene.width) * scene.height, opt);
  return crop_sphere_reference(scene.points, scene.normals, opt);
}

}  // namespace binpick
