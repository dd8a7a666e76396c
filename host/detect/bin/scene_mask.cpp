#include "host/detect/bin/scene_mask.hpp"

#include <cmath>
#include <string>

#include "host/core/error.hpp"
#include "host/detect/scene/scene_normals.hpp"

namespace binpick {
namespace {

bp_box shared_box(const std::optional<RegionBox>& box) {
  bp_box b{};
  if (!box) return b;
  if (!box->R.allFinite() || !box->t.allFinite() || !box->lo.allFinite() || !box->hi.allFinite())
    throw InputError("a region box has a non-finite value");
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) b.r[3 * r + c] = box->R(r, c);
  for (int a = 0; a < 3; ++a) b.t[a] = box->t[a], b.lo[a] = box->lo[a], b.hi[a] = box->hi[a];
  b.active = 1;
  return b;
}

}  // namespace

bp_region to_shared(const SceneRegion& region) {
  bp_region g{shared_box(region.roi), shared_box(region.bin), bp_walls{}};
  if (region.bin && region.walls && region.walls->sides != 0) {
    const BinWalls& w = *region.walls;
    if (!w.reach.allFinite() || !std::isfinite(w.height))
      throw InputError("the bin's walls have a non-finite value");
    g.walls.reach[0] = w.reach.x(), g.walls.reach[1] = w.reach.y();
    g.walls.height = w.height;
    g.walls.sides = w.sides & 15u;
    const Eigen::Vector3f cam = region.bin->R * (-region.bin->t);  // the camera, bin frame
    for (int a = 0; a < 3; ++a) g.walls.cam[a] = cam[a];
  }
  return g;
}

ocl::Buffer<std::uint8_t> scene_mask(ocl::Device& dev, const ocl::Buffer<float>& points,
                                     std::size_t n, const SceneRegion& region) {
  const bp_region g = to_shared(region);
  if (points.size() < 4 * n)
    throw std::logic_error("scene_mask: the point buffer holds fewer than n points");
  ocl::Buffer<std::uint8_t> mask(dev, n);
  if (n == 0) return mask;
  cl::Kernel k = dev.kernel("scene_mask.cl", "scene_mask");
  ocl::launch(dev, k, n, points, cl_uint(n), g, mask);
  return mask;
}

std::vector<std::uint8_t> scene_mask(ocl::Device& dev, const PointImage& points,
                                     const SceneRegion& region) {
  check_point_image(points);
  const std::size_t n = std::size_t(points.width) * points.height;
  ocl::Buffer<float> p(dev, std::span<const float>(points.xyzw), CL_MEM_READ_ONLY);
  return scene_mask(dev, p, n, region).read(dev);
}

std::vector<std::uint8_t> scene_mask_reference(const PointImage& points,
                                               const SceneRegion& region) {
  check_point_image(points);
  const bp_region g = to_shared(region);
  const std::size_t n = std::size_t(points.width) * points.height;
  std::vector<std::uint8_t> mask(n);
  for (std::size_t i = 0; i < n; ++i) {
    const float* p = &points.xyzw[4 * i];
    mask[i] = bp_region_keeps(&g, p[0], p[1], p[2], p[3]);
  }
  return mask;
}

void enqueue_masked_points(ocl::Device& dev, const ocl::Buffer<float>& points,
                           const ocl::Buffer<std::uint8_t>& mask, std::size_t n,
                           ocl::Buffer<float>& out) {
  if (n == 0) return;
  cl::Kernel k = dev.kernel("scene_mask.cl", "masked_points");
  ocl::launch(dev, k, n, points, mask, cl_uint(n), out);
}

PointImage masked_points_reference(const PointImage& points, const std::vector<std::uint8_t>& mask) {
  check_point_image(points);
  if (mask.size() != std::size_t(points.width) * points.height)
    throw InputError("the mask does not match the point image");
  PointImage out{points.width, points.height, std::vector<float>(points.xyzw.size(), 0.0f)};
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i])
      for (int c = 0; c < 4; ++c) out.xyzw[4 * i + c] = points.xyzw[4 * i + c];
  return out;
}

}  // namespace binpick
