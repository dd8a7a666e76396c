#include "host/detect/over_rim.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <utility>

#include "host/core/error.hpp"
#include "host/detect/scene_normals.hpp"

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
  cl::Kernel k = dev.kernel("scene_mask.cl", "over_rim_classes");
  ocl::launch(dev, k, n, points, cl_uint(n), test, classes, heights);
  out.classes = classes.read(dev);
  out.heights = heights.read(dev);
  return out;
}

OverRimClasses over_rim_classes_reference(const PointImage& points, const bp_over_rim& test) {
  check_point_image(points);
  const std::size_t n = std::size_t(points.width) * points.height;
  OverRimClasses out{std::vector<std::uint8_t>(n), std::vector<float>(n)};
  for (std::size_t i = 0; i < n; ++i) {
    const float* p = &points.xyzw[4 * i];
    out.classes[i] = std::uint8_t(bp_over_rim_class(&test, p[0], p[1], p[2], p[3], &out.heights[i]));
  }
  return out;
}

std::vector<std::uint8_t> reaching_in(const OverRimClasses& c, std::uint32_t width,
                                      std::uint32_t height, float max_step, std::uint32_t max_gap) {
  const std::size_t n = std::size_t(width) * height;
  if (c.classes.size() != n || c.heights.size() != n)
    throw InputError("reaching_in: the classes do not match the image size");
  std::vector<std::uint8_t> reached(n, 0);
  // Missing pixels are entered again when a path reaches them across a shorter gap (so the
  // result does not depend on which path came first); a pixel with data is entered once.
  constexpr std::uint32_t unvisited = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> best_gap(n, unvisited);
  struct Step {
    std::size_t pixel;
    float height;       // of the last pixel with data on the way here
    std::uint32_t gap;  // missing pixels crossed since it
  };
  std::vector<Step> queue;
  for (std::size_t i = 0; i < n; ++i)
    if (c.classes[i] == BP_OVER_RIM_OUT) {
      reached[i] = 1;
      best_gap[i] = 0;
      queue.push_back({i, c.heights[i], 0});
    }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const Step s = queue[head];
    const std::size_t u = s.pixel % width, v = s.pixel / width;
    const std::size_t next[4] = {u > 0 ? s.pixel - 1 : n, u + 1 < width ? s.pixel + 1 : n,
                                 v > 0 ? s.pixel - width : n, v + 1 < height ? s.pixel + width : n};
    for (const std::size_t j : next) {
      if (j == n) continue;
      const std::uint8_t cls = c.classes[j];
      if (cls == BP_OVER_RIM_NODATA) {
        const std::uint32_t gap = s.gap + 1;
        if (gap > max_gap || gap >= best_gap[j]) continue;
        best_gap[j] = gap;
        queue.push_back({j, s.height, gap});
      } else if (cls != BP_OVER_RIM_NO && !reached[j] &&
                 std::fabs(c.heights[j] - s.height) <= max_step) {
        reached[j] = 1;
        best_gap[j] = 0;
        queue.push_back({j, c.heights[j], 0});
      }
    }
  }
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
  constexpr std::uint32_t unvisited = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> best_gap(n);
  std::vector<std::pair<std::size_t, std::uint32_t>> queue;  // pixel, missing pixels crossed
  for (const FoundPlane& pl : planes) {
    const auto on = [&](std::size_t i) {
      const float* p = &xyzw[4 * i];
      return std::fabs(pl.normal.x() * p[0] + pl.normal.y() * p[1] + pl.normal.z() * p[2] +
                       pl.d) <= tol;
    };
    std::fill(best_gap.begin(), best_gap.end(), unvisited);
    queue.clear();
    for (std::size_t i = 0; i < n; ++i)
      if (start[i] && xyzw[4 * i + 3] != 0.0f && on(i)) best_gap[i] = 0, queue.push_back({i, 0});
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const auto [i, g] = queue[head];
      const std::size_t u = i % width, v = i / width;
      const std::size_t next[4] = {u > 0 ? i - 1 : n, u + 1 < width ? i + 1 : n,
                                   v > 0 ? i - width : n, v + 1 < height ? i + width : n};
      for (const std::size_t j : next) {
        if (j == n) continue;
        if (xyzw[4 * j + 3] == 0.0f) {
          if (g + 1 > max_gap || g + 1 >= best_gap[j]) continue;
          best_gap[j] = g + 1;
          queue.push_back({j, g + 1});
        } else if (best_gap[j] != 0 && on(j)) {
          best_gap[j] = 0;
          reached[j] = 1;
          queue.push_back({j, 0});
        }
      }
    }
  }
}

}  // namespace binpick
