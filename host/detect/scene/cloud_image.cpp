#include "host/detect/scene/cloud_image.hpp"

#include <algorithm>
#include <cmath>

#include "host/core/error.hpp"

namespace binpick {
namespace {

// A pixel no point fell in but a neighbour's did is a gap between samples: it takes the
// nearest neighbouring point. Every pixel still empty saw nothing: it gets a point far behind
// everything (on its ray), so a pose that puts the part there is seen through.
void fill_holes_and_background(CloudImage& image, float far) {
  const bp_camera& cam = image.camera;
  const std::vector<float> in = image.points.xyzw;
  const long w = cam.width, h = cam.height;
  for (long v = 0; v < h; ++v)
    for (long u = 0; u < w; ++u) {
      float* px = &image.points.xyzw[std::size_t(v * w + u) * 4];
      if (px[3] != 0) continue;
      const float* best = nullptr;
      for (long dv = -1; dv <= 1; ++dv)
        for (long du = -1; du <= 1; ++du) {
          if (u + du < 0 || v + dv < 0 || u + du >= w || v + dv >= h) continue;
          const float* q = &in[std::size_t((v + dv) * w + u + du) * 4];
          if (q[3] != 0 && (!best || q[2] < best[2])) best = q;
        }
      if (best) {
        std::copy(best, best + 4, px);
      } else {
        px[0] = (float(u) - cam.cx) * far / cam.fx;
        px[1] = (float(v) - cam.cy) * far / cam.fy;
        px[2] = far;
        px[3] = 1.0f;
      }
    }
}

}  // namespace

CloudImage cloud_point_image(const PointCloud& cloud, float pitch) {
  if (!(pitch > 0) || !std::isfinite(pitch))
    throw InputError("cloud image pixel pitch must be positive (mm)");
  std::vector<float> depths;
  float lo_x = INFINITY, hi_x = -INFINITY, lo_y = INFINITY, hi_y = -INFINITY;
  for (const Eigen::Vector3f& p : cloud.points) {
    if (!(p.z() > 0)) continue;
    depths.push_back(p.z());
    lo_x = std::min(lo_x, p.x() / p.z()), hi_x = std::max(hi_x, p.x() / p.z());
    lo_y = std::min(lo_y, p.y() / p.z()), hi_y = std::max(hi_y, p.y() / p.z());
  }
  if (depths.empty()) throw InputError("no point of the cloud lies in front of the camera (z > 0)");
  std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
  double f = depths[depths.size() / 2] / pitch;
  const double span = std::max(hi_x - lo_x, hi_y - lo_y);
  if (span * f + 3 > kMaxCloudImageSide) f = (kMaxCloudImageSide - 3) / span;
  CloudImage out;
  bp_camera& cam = out.camera;
  cam.fx = cam.fy = float(f);
  // One pixel of margin on each side, so every point rounds to a pixel inside.
  cam.cx = float(1.0 - f * lo_x);
  cam.cy = float(1.0 - f * lo_y);
  cam.depth_scale = 1.0f;
  cam.width = std::uint32_t(std::ceil(f * (hi_x - lo_x))) + 3;
  cam.height = std::uint32_t(std::ceil(f * (hi_y - lo_y))) + 3;
  out.points.width = cam.width;
  out.points.height = cam.height;
  out.points.xyzw.assign(std::size_t(cam.width) * cam.height * 4, 0.0f);
  for (const Eigen::Vector3f& p : cloud.points) {
    if (!(p.z() > 0)) continue;
    const auto u = std::lround(cam.fx * p.x() / p.z() + cam.cx);
    const auto v = std::lround(cam.fy * p.y() / p.z() + cam.cy);
    if (u < 0 || v < 0 || u >= long(cam.width) || v >= long(cam.height)) continue;
    float* px = &out.points.xyzw[(std::size_t(v) * cam.width + std::size_t(u)) * 4];
    if (px[3] != 0 && px[2] <= p.z()) continue;
    px[0] = p.x(), px[1] = p.y(), px[2] = p.z(), px[3] = 1.0f;
  }
  const float farthest = *std::max_element(depths.begin(), depths.end());
  out.depth_scale = farthest < 6500.0f ? 0.1f : 1.0f;
  out.depth.assign(std::size_t(cam.width) * cam.height, 0);
  for (std::size_t i = 0; i < out.depth.size(); ++i)
    if (out.points.xyzw[4 * i + 3] != 0)
      out.depth[i] = std::uint16_t(
          std::clamp(std::lround(out.points.xyzw[4 * i + 2] / out.depth_scale), 1L, 65535L));
  fill_holes_and_background(out, 10.0f * farthest);
  return out;
}

}  // namespace binpick
