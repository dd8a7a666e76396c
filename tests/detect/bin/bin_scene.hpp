// A bin "photographed" analytically for the bin and mask tests: a floor slab, four walls whose
// tops form the rim, a few spheres for parts, the ground outside, ray-cast exactly per pixel of
// a 320 x 240 camera that looks at the floor's centre from 1000 mm, straight down or tilted
// about the bin's x axis, the bin turned by a yaw about its vertical axis.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "host/detect/scene/depth_to_points.hpp"

namespace binpick::test {

struct BinSceneSpec {
  double W = 400, D = 300, H = 180, wall = 12;  // interior (mm), wall thickness
  double tilt_deg = 0, yaw_deg = 0;
  double distance = 1000;                       // camera to the floor's centre
  std::vector<Eigen::Vector4d> spheres = {      // x, y, z, radius in the bin frame
      {-100, -50, 25, 25}, {60, 40, 25, 25}, {120, -80, 30, 30}, {-20, 90, 20, 20}};
  double depth_scale = 0.1;
  bool wall_px = true;  // false: no +x wall nor rim (seen through to the ground, as a mesh's)
  // > 0: the -y wall is a mesh's, vertical bars 4 mm wide this far apart under a 10 mm rim bar
  // (the parts behind it are seen between the bars).
  double bars_my = 0;
  // More axis-aligned boxes in the bin frame (lo, hi): a robot arm, a fixture.
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> boxes;
};

struct BinScene {
  bp_camera cam{520.0f, 520.0f, 159.5f, 119.5f, 0.1f, 320, 240, 0};
  DepthImage depth;
  Eigen::Matrix3d bin_to_cam = Eigen::Matrix3d::Identity();  // rotation, bin frame -> camera
  Eigen::Vector3d floor_centre = Eigen::Vector3d::Zero();     // the bin frame's origin, camera
  // A camera-frame point in the bin frame.
  Eigen::Vector3d to_bin(const Eigen::Vector3d& p) const {
    return bin_to_cam.transpose() * (p - floor_centre);
  }
};

namespace detail {
// Entry distance of the ray o + t d into an axis-aligned box (infinity if missed).
inline double ray_box(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& lo,
                      const Eigen::Vector3d& hi) {
  double t0 = 0, t1 = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-12) {
      if (o[a] < lo[a] || o[a] > hi[a]) return t1;
      continue;
    }
    double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta), t1 = std::min(t1, tb);
  }
  return t0 <= t1 && t0 > 0 ? t0 : std::numeric_limits<double>::infinity();
}
inline double ray_sphere(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& c,
                         double r) {
  const Eigen::Vector3d oc = o - c;
  const double b = oc.dot(d), cc = oc.squaredNorm() - r * r, a = d.squaredNorm();
  const double disc = b * b - a * cc;
  if (disc < 0) return std::numeric_limits<double>::infinity();
  const double t = (-b - std::sqrt(disc)) / a;
  return t > 0 ? t : std::numeric_limits<double>::infinity();
}
}  // namespace detail

inline BinScene make_bin_scene(const BinSceneSpec& s = {}) {
  BinScene out;
  const double th = s.tilt_deg * M_PI / 180, yaw = s.yaw_deg * M_PI / 180;
  // The camera in the bin frame: on a circle about the bin's x axis through the floor centre.
  const Eigen::Vector3d C(0, -s.distance * std::sin(th), s.distance * std::cos(th));
  const Eigen::Vector3d f = -C.normalized(), r(1, 0, 0), y = f.cross(r);
  Eigen::Matrix3d M;  // rows: camera axes in the (unturned) bin frame
  M.row(0) = r, M.row(1) = y, M.row(2) = f;
  const Eigen::Matrix3d yaw_R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  // bin -> camera: undo the yaw (the bin is turned, the camera is not), then M.
  out.bin_to_cam = M * yaw_R.transpose();
  out.floor_centre = M * (-C);
  const double hw = s.W / 2, hd = s.D / 2, t = s.wall;
  struct Box { Eigen::Vector3d lo, hi; };
  std::vector<Box> boxes = {
      {{-hw - t, -hd - t, -20}, {hw + t, hd + t, 0}},       // floor slab
      {{-hw - t, -hd - t, 0}, {-hw, hd + t, s.H}},          // walls
      {{hw, -hd - t, 0}, {hw + t, hd + t, s.H}},
      {{-hw, -hd - t, 0}, {hw, -hd, s.H}},
      {{-hw, hd, 0}, {hw, hd + t, s.H}},
      {{-3000, -3000, -40}, {3000, 3000, -20}},             // the ground
  };
  if (s.bars_my > 0) {
    boxes.erase(boxes.begin() + 3);  // the -y wall
    boxes.push_back({{-hw - t, -hd - t, s.H - 10}, {hw + t, -hd, s.H}});
    for (double x = -hw; x <= hw; x += s.bars_my)
      boxes.push_back({{x - 2, -hd - t, 0}, {x + 2, -hd, s.H - 10}});
    for (double z = 0; z < s.H - 10; z += 1.5 * s.bars_my)
      boxes.push_back({{-hw - t, -hd - t - 4, z}, {hw + t, -hd - t, z + 4}});
  }
  if (!s.wall_px) boxes.erase(boxes.begin() + 2);
  for (const auto& [lo, hi] : s.boxes) boxes.push_back({lo, hi});
  out.cam.depth_scale = float(s.depth_scale);
  out.depth = {out.cam.width, out.cam.height,
               std::vector<std::uint16_t>(std::size_t(out.cam.width) * out.cam.height, 0)};
  for (std::uint32_t v = 0; v < out.cam.height; ++v)
    for (std::uint32_t u = 0; u < out.cam.width; ++u) {
      const Eigen::Vector3d dc((u - out.cam.cx) / out.cam.fx, (v - out.cam.cy) / out.cam.fy, 1.0);
      // Into the bin frame: the camera sits at yaw_R C, its axes turned by the yaw.
      const Eigen::Vector3d o = yaw_R * C, d = out.bin_to_cam.transpose() * dc;
      double best = std::numeric_limits<double>::infinity();
      for (const Box& b : boxes) best = std::min(best, detail::ray_box(o, d, b.lo, b.hi));
      for (const auto& sp : s.spheres)
        best = std::min(best, detail::ray_sphere(o, d, sp.head<3>(), sp[3]));
      if (!std::isfinite(best)) continue;
      out.depth.raw[std::size_t(v) * out.cam.width + u] =
          std::uint16_t(std::lround(best / s.depth_scale));  // t is the camera z (dc.z = 1)
    }
  return out;
}

// Holes over about `fraction` of the pixels: blobs and stripes, the way a structured-light
// sensor loses depth (shadows, grazing angles, dark metal).
inline void punch_holes(DepthImage& depth, double fraction, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0, 1);
  const std::size_t n = depth.raw.size();
  const auto holes = [&] {
    return std::size_t(std::count(depth.raw.begin(), depth.raw.end(), std::uint16_t(0)));
  };
  const std::size_t target = std::size_t(fraction * double(n));
  int k = 0;
  while (holes() < target && k < 10000) {
    ++k;
    if (k % 3 == 0) {  // a stripe a few pixels high, across much of the image
      const std::uint32_t v0 = std::uint32_t(U(rng) * depth.height), hgt = 2 + std::uint32_t(U(rng) * 6);
      const std::uint32_t u0 = std::uint32_t(U(rng) * depth.width * 0.5);
      for (std::uint32_t v = v0; v < std::min(depth.height, v0 + hgt); ++v)
        for (std::uint32_t u = u0; u < std::min(depth.width, u0 + depth.width / 2); ++u)
          depth.raw[std::size_t(v) * depth.width + u] = 0;
    } else {  // a blob
      const double cu = U(rng) * depth.width, cv = U(rng) * depth.height, r = 4 + U(rng) * 18;
      for (std::uint32_t v = 0; v < depth.height; ++v)
        for (std::uint32_t u = 0; u < depth.width; ++u)
          if ((u - cu) * (u - cu) + (v - cv) * (v - cv) <= r * r)
            depth.raw[std::size_t(v) * depth.width + u] = 0;
    }
  }
}

}  // namespace binpick::test
