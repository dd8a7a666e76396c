// A small scene for the refinement and verification tests: an L-bracket at a known pose in
// front of a floor, "rendered" by projecting dense surface samples into a z-buffer, and the
// part's model cloud (voxel subsampled) with the geometry the fit needs.
#pragma once

#include <functional>
#include <random>

#include <Eigen/Geometry>

#include "host/detect/refine/pose_fit.hpp"
#include "host/detect/refine/pose_refine.hpp"
#include "host/train/surface_sampling.hpp"
#include "host/train/voxel_subsample.hpp"
#include "tests/support/test_meshes.hpp"

namespace binpick::test {

struct FitScene {
  bp_camera cam{500.0f, 500.0f, 160.0f, 120.0f, 1.0f, 320, 240, 0};
  PointCloud model;  // voxel subsampled, unit normals
  FitGeometry geometry;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  PointImage image;
};

// The bracket at a tilted pose 500 mm in front of the camera (its centroid at `at`), a floor
// 40 mm behind it; noise sigma (mm) on every measured depth. raise (optional): how much nearer
// the camera (mm) the measured surface lies than the model at a model point: a similar but
// different object.
inline FitScene make_fit_scene(double noise = 0.0, unsigned seed = 1,
                               const std::function<double(const Eigen::Vector3f&)>& raise = {},
                               const Eigen::Vector3d& at = Eigen::Vector3d(-10, 5, 500)) {
  FitScene s;
  const Mesh mesh = l_bracket();
  const PointCloud dense = sample_surface(mesh, 60000);
  s.geometry.voxel_size = 2.7f;
  s.model = voxel_subsample_reference(sample_surface(mesh, 20000), s.geometry.voxel_size).cloud;
  s.geometry.diameter = 54.0f;
  s.geometry.centroid = model_centroid(s.model);
  s.R = Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 0.5).normalized()).toRotationMatrix();
  s.t = at - s.R * s.geometry.centroid;
  s.image.width = s.cam.width;
  s.image.height = s.cam.height;
  s.image.xyzw.assign(std::size_t(s.cam.width) * s.cam.height * 4, 0.0f);
  std::vector<float> zbuf(std::size_t(s.cam.width) * s.cam.height, 540.0f);  // the floor
  for (const Eigen::Vector3f& m : dense.points) {
    Eigen::Vector3d q = s.R * m.cast<double>() + s.t;
    if (raise) q *= (q.z() - raise(m)) / q.z();  // along the ray: the pixel stays
    const long u = std::lround(s.cam.fx * q.x() / q.z() + s.cam.cx);
    const long v = std::lround(s.cam.fy * q.y() / q.z() + s.cam.cy);
    if (u < 0 || v < 0 || u >= long(s.cam.width) || v >= long(s.cam.height)) continue;
    float& z = zbuf[std::size_t(v) * s.cam.width + std::size_t(u)];
    z = std::min(z, float(q.z()));
  }
  std::mt19937 rng(seed);
  std::normal_distribution<float> N(0.0f, float(noise));
  for (std::uint32_t v = 0; v < s.cam.height; ++v)
    for (std::uint32_t u = 0; u < s.cam.width; ++u) {
      const std::size_t i = std::size_t(v) * s.cam.width + u;
      const float z = zbuf[i] + (noise > 0 ? N(rng) : 0.0f);
      float* p = &s.image.xyzw[i * 4];
      p[0] = (float(u) - s.cam.cx) * z / s.cam.fx;
      p[1] = (float(v) - s.cam.cy) * z / s.cam.fy;
      p[2] = z;
      p[3] = 1.0f;
    }
  return s;
}

inline double rotation_error_deg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle() * 180.0 / 3.14159265358979;
}

}  // namespace binpick::test
