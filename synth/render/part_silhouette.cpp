#include "synth/render/part_silhouette.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "host/core/error.hpp"

namespace binpick {

void silhouettes_from_atlas(const std::uint32_t* ids, const float* zbuffer, const AtlasBatch& batch,
                            const RenderCamera& camera, std::vector<PartSilhouette>& out) {
  const float n = float(camera.near_mm), f = float(camera.far_mm);
  for (const AtlasTile& t : batch.tiles) {
    if (std::size_t(t.part) >= out.size()) throw InputError("silhouettes: a tile of an unknown part");
    PartSilhouette& s = out[std::size_t(t.part)];
    s = {};
    const std::uint32_t id = std::uint32_t(t.part) + 1;
    for (int y = 0; y < t.image.h; ++y) {
      const std::size_t row = std::size_t(t.atlas_y + y) * std::size_t(batch.width) + std::size_t(t.atlas_x);
      for (int x = 0; x < t.image.w; ++x) {
        if (ids[row + std::size_t(x)] != id) continue;
        const float b = zbuffer[row + std::size_t(x)];
        // Equation 1, in float like bin_gbuffer.comp, so a part seen unoccluded has the depth
        // the scene's depth image has there.
        s.pixels.push_back(std::uint32_t(t.image.y + y) * camera.width + std::uint32_t(t.image.x + x));
        s.depth_mm.push_back(n * f / (f + b * (n - f)));
      }
    }
  }
}

namespace {

// Framebuffer position in 1/256 pixel (the rasteriser's sub-pixel grid): pixel (u, v) of the
// image is the framebuffer square [u, u + 1) x [v, v + 1), centre (u + 0.5, v + 0.5).
constexpr double kSubpixel = 256.0;

struct ScreenVertex {
  std::int64_t x = 0, y = 0;  // snapped
  double inv_z = 0;
};

std::int64_t edge(const ScreenVertex& a, const ScreenVertex& b, std::int64_t px, std::int64_t py) {
  return (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x);
}

// With the triangle's signed area positive, the interior is on the positive side of each edge;
// a centre exactly on an edge belongs to the triangle only for a top edge (horizontal, interior
// below) or a left edge (going up in y-down coordinates).
bool top_left(const ScreenVertex& a, const ScreenVertex& b) {
  const std::int64_t dx = b.x - a.x, dy = b.y - a.y;
  return (dy == 0 && dx > 0) || dy < 0;
}

}  // namespace

PartSilhouette part_silhouette_reference(const Mesh& part, const Eigen::Isometry3d& part_to_camera,
                                         const RenderCamera& camera, bool cull_back_faces) {
  const std::size_t w = camera.width, h = camera.height;
  std::vector<double> nearest(w * h, std::numeric_limits<double>::infinity());
  for (const auto& tri : part.triangles) {
    std::array<ScreenVertex, 3> v;
    bool in_range = true;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d c = part_to_camera * part.positions[tri[k]].cast<double>();
      in_range = in_range && c.z() > camera.near_mm && c.z() < camera.far_mm;
      const Eigen::Vector2d uv = project(camera, c);
      v[k] = {std::llround((uv.x() + 0.5) * kSubpixel), std::llround((uv.y() + 0.5) * kSubpixel),
              1.0 / c.z()};
    }
    if (!in_range) continue;
    // Vulkan's signed area is minus this one; counter-clockwise (its front face) is area < 0.
    std::int64_t area = edge(v[0], v[1], v[2].x, v[2].y);
    if (area == 0 || (cull_back_faces && area > 0)) continue;
    if (area < 0) std::swap(v[1], v[2]), area = -area;
    const auto lo = [](std::int64_t a, std::int64_t b, std::int64_t c) { return std::min({a, b, c}); };
    const auto hi = [](std::int64_t a, std::int64_t b, std::int64_t c) { return std::max({a, b, c}); };
    // Pixels whose centre (u * 256 + 128) can lie in the triangle's bounding box.
    const auto first = [](std::int64_t s) { return std::int64_t(std::ceil((double(s) - 128) / kSubpixel)); };
    const auto last = [](std::int64_t s) { return std::int64_t(std::floor((double(s) - 128) / kSubpixel)); };
    const std::int64_t u0 = std::max<std::int64_t>(first(lo(v[0].x, v[1].x, v[2].x)), 0);
    const std::int64_t u1 = std::min<std::int64_t>(last(hi(v[0].x, v[1].x, v[2].x)), std::int64_t(w) - 1);
    const std::int64_t v0 = std::max<std::int64_t>(first(lo(v[0].y, v[1].y, v[2].y)), 0);
    const std::int64_t v1 = std::min<std::int64_t>(last(hi(v[0].y, v[1].y, v[2].y)), std::int64_t(h) - 1);
    for (std::int64_t pv = v0; pv <= v1; ++pv)
      for (std::int64_t pu = u0; pu <= u1; ++pu) {
        const std::int64_t px = pu * 256 + 128, py = pv * 256 + 128;
        std::array<std::int64_t, 3> e{edge(v[1], v[2], px, py), edge(v[2], v[0], px, py),
                                      edge(v[0], v[1], px, py)};
        bool inside = true;
        for (int k = 0; k < 3; ++k) {
          const ScreenVertex &a = v[(k + 1) % 3], &b = v[(k + 2) % 3];
          inside = inside && (e[k] > 0 || (e[k] == 0 && top_left(a, b)));
        }
        if (!inside) continue;
        // 1/z is linear across the screen (so is the z-buffer value, a + b / z).
        const double inv_z = (double(e[0]) * v[0].inv_z + double(e[1]) * v[1].inv_z +
                              double(e[2]) * v[2].inv_z) / double(area);
        double& d = nearest[std::size_t(pv) * w + std::size_t(pu)];
        d = std::min(d, 1.0 / inv_z);
      }
  }
  PartSilhouette out;
  for (std::size_t i = 0; i < nearest.size(); ++i)
    if (std::isfinite(nearest[i])) {
      out.pixels.push_back(std::uint32_t(i));
      out.depth_mm.push_back(float(nearest[i]));
    }
  return out;
}

}  // namespace binpick
