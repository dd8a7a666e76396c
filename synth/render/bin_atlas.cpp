#include "synth/render/bin_atlas.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "host/core/error.hpp"

namespace binpick {

PixelRect projected_rect(const Mesh& part, const Eigen::Isometry3d& part_to_camera,
                         const RenderCamera& camera) {
  const PixelRect whole{0, 0, int(camera.width), int(camera.height)};
  double u0 = INFINITY, v0 = INFINITY, u1 = -INFINITY, v1 = -INFINITY, z_max = -INFINITY;
  const Eigen::Matrix3d r = part_to_camera.linear();
  const Eigen::Vector3d t = part_to_camera.translation();
  for (const Eigen::Vector3f& p : part.positions) {
    const Eigen::Vector3d c = r * p.cast<double>() + t;
    if (!(c.z() > camera.near_mm)) return whole;
    z_max = std::max(z_max, c.z());
    const Eigen::Vector2d uv = project(camera, c);
    u0 = std::min(u0, uv.x()), u1 = std::max(u1, uv.x());
    v0 = std::min(v0, uv.y()), v1 = std::max(v1, uv.y());
  }
  if (part.positions.empty() || !std::isfinite(u0 + u1 + v0 + v1)) return {};
  // Pixel centres are at integers: those inside [u0, u1] are ceil(u0)..floor(u1); one pixel of
  // padding absorbs the rasteriser's rounding of vertex positions.
  const double x0 = std::max(std::floor(u0) - 1, 0.0), y0 = std::max(std::floor(v0) - 1, 0.0);
  const double x1 = std::min(std::ceil(u1) + 1, double(camera.width) - 1);
  const double y1 = std::min(std::ceil(v1) + 1, double(camera.height) - 1);
  if (x1 < x0 || y1 < y0) return {};
  return {int(x0), int(y0), int(x1 - x0) + 1, int(y1 - y0) + 1};
}

std::vector<AtlasBatch> pack_atlas(const std::vector<PixelRect>& rects, int atlas_width,
                                   int atlas_height) {
  std::vector<int> order(rects.size());
  std::iota(order.begin(), order.end(), 0);
  // Tallest first keeps the shelves tight.
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return rects[a].h > rects[b].h; });
  std::vector<AtlasBatch> batches;
  int shelf_y = 0, shelf_h = 0, x = 0;
  for (int part : order) {
    const PixelRect& r = rects[part];
    if (r.empty()) continue;
    if (r.w > atlas_width || r.h > atlas_height)
      throw InputError("atlas tile larger than the atlas");
    if (batches.empty()) batches.emplace_back(), shelf_y = shelf_h = x = 0;
    if (x + r.w > atlas_width) shelf_y += shelf_h, shelf_h = 0, x = 0;  // next shelf
    if (shelf_y + r.h > atlas_height) batches.emplace_back(), shelf_y = shelf_h = x = 0;
    AtlasBatch& batch = batches.back();
    batch.tiles.push_back({part, r, x, shelf_y});
    x += r.w;
    shelf_h = std::max(shelf_h, r.h);
    batch.width = std::max(batch.width, x);
    batch.height = std::max(batch.height, shelf_y + shelf_h);
  }
  return batches;
}

}  // namespace binpick
