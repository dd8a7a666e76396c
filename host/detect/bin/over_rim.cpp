#include "host/detect/bin/over_rim.hpp"

#include <cmath>
#include <string>

#include "host/core/error.hpp"
#include "host/detect/bin/gap_flood.hpp"
#include "host/detect/scene/scene_normals.hpp"

namespace binpick {

bp_over_rim over_rim_test(const BinFit& bin, double clearance) {
  if (!bin.found) throw InputError("over_rim_test: no bin was found");
  if (!bin.axes.allFinite() || !bin.origin.allFinite() || !bin.interior.allFinite() ||
      !std::isfinite(clearance))
    throw InputError("over_rim_test: the bin has a non-finite value");
  bp_over_rim g{};
  const Eigen::Matrix3d r = bin.axes.transpose();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) g.r[3 * i + j] = float(r(i, j));
  for (int a = 0; a < 3; ++a) g.t[a] = float(bin.origin[a]);
  g.reach[0] = float(0.5 * bin.interior.x() + clearance);
  g.reach[1] = float(0.5 * bin.interior.y() + clearance);
  g.lift = float(bin.interior.z() + clearance);
  g.sides = 15u & ~bin.unseen_walls;
  return g;
}

OverRimClasses over_rim_classes(ocl::Device& dev, const ocl::Buffer<float>& points,
                                std::size_t n, const bp_over_rim& test) {
  if (points.size() < 4 * n)
    throw std::logic_error("over_rim_classes: the point buffer holds fewer than n points");
  OverRimClasses out;
  if (n == 0) return out;
  ocl::Buffer<std::uint8_t> classes(dev, n);
  ocl::Buffer<float> heights(dev, n);
  ocl::Buffer<cl_uint> beyond(dev, 1);
  beyond.fill(dev, 0u);
  cl::Kernel k = dev.kernel("scene_mask.cl", "over_rim_classes");
  ocl::launch(dev, k, n, points, cl_uint(n), test, classes, heights, beyond);
  out.beyond = beyond.read(dev)[0];
  if (out.beyond == 0) return out;  // nothing to flood from: 15 MB not read at 2064 x 1544
  out.classes = classes.read(dev);
  out.heights = heights.read(dev);
  return out;
}

OverRimClasses over_rim_classes_reference(const PointImage& points, const bp_over_rim& test) {
  check_point_image(points);
  const std::size_t n = std::size_t(points.width) * points.height;
  OverRimClasses out{std::vector<std::uint8_t>(n), std::vector<float>(n), 0};
  for (std::size_t i = 0; i < n; ++i) {
    const float* p = &points.xyzw[4 * i];
    out.classes[i] = std::uint8_t(bp_over_rim_class(&test, p[0], p[1], p[2], p[3], &out.heights[i]));
    out.beyond += out.classes[i] == BP_OVER_RIM_OUT;
  }
  return out;
}

std::vector<std::uint8_t> reaching_in(const OverRimClasses& c, std::uint32_t width,
                                      std::uint32_t height, float max_step, std::uint32_t max_gap) {
  const std::size_t n = std::size_t(width) * height;
  if (c.classes.size() != n || c.heights.size() != n)
    throw InputError("reaching_in: the classes do not match the image size");
  std::vector<std::size_t> seeds;
  for (std::size_t i = 0; i < n; ++i)
    if (c.classes[i] == BP_OVER_RIM_OUT) seeds.push_back(i);
  std::vector<std::uint8_t> reached(n, 0);
  const auto missing = [&](std::size_t j) { return c.classes[j] == BP_OVER_RIM_NODATA; };
  const auto joins = [&](std::size_t last, std::size_t j) {
    return c.classes[j] != BP_OVER_RIM_NO && std::fabs(c.heights[j] - c.heights[last]) <= max_step;
  };
  for (const std::size_t i : flood_with_gaps(width, height, seeds, missing, joins, max_gap))
    reached[i] = 1;
  return reached;
}

std::vector<FoundPlane> reaching_planes(ocl::Device& dev, const std::vector<float>& xyzw,
                                        std::uint32_t width, std::uint32_t height,
                                        const std::vector<std::uint8_t>& reached, float tol) {
  const std::size_t n = std::size_t(width) * height;
  if (xyzw.size() != 4 * n || reached.size() != n)
    throw InputError("reaching_planes: the points do not match the image size");
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i) count += reached[i] && xyzw[4 * i + 3] != 0.0f;
  if (count < 50) return {};
  PlaneSamples s;
  s.stride = sample_stride(count, 20000);
  s.width = width, s.height = height;
  for (std::uint32_t v = 0; v < height; v += s.stride)
    for (std::uint32_t u = 0; u < width; u += s.stride) {
      const std::size_t i = std::size_t(v) * width + u;
      if (!reached[i] || xyzw[4 * i + 3] == 0.0f) continue;
      s.points.emplace_back(xyzw[4 * i], xyzw[4 * i + 1], xyzw[4 * i + 2]);
      s.u.push_back(u);
      s.v.push_back(v);
    }
  PlaneSearch opt;
  opt.tol = tol;
  opt.min_fraction = 0.05;  // a face of the thing, not a corner of it
  opt.max_planes = 3;
  return s.points.size() < 50 ? std::vector<FoundPlane>{} : find_planes(dev, s, opt);
}

void follow_planes(const std::vector<float>& xyzw, std::uint32_t width, std::uint32_t height,
                   const std::vector<FoundPlane>& planes, float tol, std::uint32_t max_gap,
                   std::vector<std::uint8_t>& reached) {
  const std::size_t n = std::size_t(width) * height;
  if (xyzw.size() != 4 * n || reached.size() != n)
    throw InputError("follow_planes: the points do not match the image size");
  const std::vector<std::uint8_t> start = reached;
  const auto missing = [&](std::size_t j) { return xyzw[4 * j + 3] == 0.0f; };
  for (const FoundPlane& pl : planes) {
    const auto on = [&](std::size_t i) {
      const float* p = &xyzw[4 * i];
      return std::fabs(pl.normal.x() * p[0] + pl.normal.y() * p[1] + pl.normal.z() * p[2] +
                       pl.d) <= tol;
    };
    std::vector<std::size_t> seeds;
    for (std::size_t i = 0; i < n; ++i)
      if (start[i] && !missing(i) && on(i)) seeds.push_back(i);
    const auto joins = [&](std::size_t, std::size_t j) { return on(j); };
    for (const std::size_t i :
         flood_with_gaps(width, height, seeds, missing, joins, max_gap, /*path_independent=*/true))
      reached[i] = 1;
  }
}

}  // namespace binpick
