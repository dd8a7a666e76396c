#include "tests/support/plate_scene.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "host/train/surface_sampling.hpp"
#include "synth/parts/builtin_parts.hpp"

namespace binpick::test {

bp_camera plate_camera() { return bp_camera{500.0f, 500.0f, 160.0f, 120.0f, 1.0f, 320, 240, 0}; }

Eigen::Isometry3d plate_pose() {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(0.1, Eigen::Vector3d(1, 1, 0).normalized()) *
                   Eigen::AngleAxisd(3.14159265358979, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  pose.translation() = Eigen::Vector3d(0, 0, 500);
  return pose;
}

namespace {

// The plate's depth at `pose` in every pixel (a z-buffer of dense surface samples), infinite
// where it is not.
std::vector<float> plate_depths(const bp_camera& cam, const Eigen::Isometry3d& pose) {
  std::vector<float> zbuf(std::size_t(cam.width) * cam.height, INFINITY);
  const PointCloud dense = sample_surface(make_builtin_part("plate"), 200000);
  for (const Eigen::Vector3f& m : dense.points) {
    const Eigen::Vector3d q = pose * m.cast<double>();
    const long u = std::lround(cam.fx * q.x() / q.z() + cam.cx);
    const long v = std::lround(cam.fy * q.y() / q.z() + cam.cy);
    if (u < 0 || v < 0 || u >= long(cam.width) || v >= long(cam.height)) continue;
    float& z = zbuf[std::size_t(v) * cam.width + std::size_t(u)];
    z = std::min(z, float(q.z()));
  }
  return zbuf;
}

// A point image of the camera's size: pixel i (ray: its direction at depth 1) at depth(i, ray)
// along its ray plus Gaussian noise of sigma (seeded); no depth where has_depth(i) is false.
template <class Depth, class HasDepth>
PointImage noisy_image(const bp_camera& cam, float sigma, unsigned seed, Depth depth,
                       HasDepth has_depth) {
  PointImage image;
  image.width = cam.width;
  image.height = cam.height;
  image.xyzw.assign(std::size_t(cam.width) * cam.height * 4, 0.0f);
  std::mt19937 rng(seed);
  std::normal_distribution<float> N(0.0f, sigma);
  for (std::uint32_t v = 0; v < cam.height; ++v)
    for (std::uint32_t u = 0; u < cam.width; ++u) {
      const std::size_t i = std::size_t(v) * cam.width + u;
      const Eigen::Vector3d ray((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0);
      const float z = depth(i, ray) + N(rng);
      float* p = &image.xyzw[i * 4];
      p[0] = float(ray.x()) * z, p[1] = float(ray.y()) * z, p[2] = z;
      p[3] = has_depth(i) ? 1.0f : 0.0f;
    }
  return image;
}

}  // namespace

PointImage plate_over_plane(const bp_camera& cam, const Eigen::Isometry3d& pose,
                            bool holes_without_depth) {
  const Eigen::Vector3d up = pose.linear() * Eigen::Vector3d::UnitZ();  // towards the camera
  const Eigen::Vector3d beneath = pose.translation() - 0.75 * up;  // the plate beneath's top face
  const std::vector<float> zbuf = plate_depths(cam, pose);
  return noisy_image(
      cam, 0.5f, 3,
      [&](std::size_t i, const Eigen::Vector3d& ray) {
        const double plane = up.dot(beneath) / up.dot(ray);  // depth of the plane at this pixel
        return std::min(zbuf[i], float(plane));
      },
      [&](std::size_t i) { return !(holes_without_depth && !std::isfinite(zbuf[i])); });
}

PointImage without_depth_in_patches(PointImage image, std::uint32_t patch) {
  for (std::uint32_t v = 0; v < image.height; ++v)
    for (std::uint32_t u = 0; u < image.width; ++u)
      if ((u / patch + v / patch) % 2 == 0) image.xyzw[(std::size_t(v) * image.width + u) * 4 + 3] = 0;
  return image;
}

PointImage plate_over_floor(const bp_camera& cam, const Eigen::Isometry3d& pose, float floor_z) {
  const std::vector<float> zbuf = plate_depths(cam, pose);
  return noisy_image(
      cam, 0.3f, 5, [&](std::size_t i, const Eigen::Vector3d&) { return std::min(zbuf[i], floor_z); },
      [](std::size_t) { return true; });
}

PointImage plane_of_plate_face(const bp_camera& cam, const Eigen::Isometry3d& pose) {
  const Eigen::Vector3d up = pose.linear() * Eigen::Vector3d::UnitZ();  // towards the camera
  const Eigen::Vector3d face = pose.translation() + 0.75 * up;
  std::vector<float> depth(std::size_t(cam.width) * cam.height, 0.0f);
  for (std::uint32_t v = 0; v < cam.height; ++v)
    for (std::uint32_t u = 0; u < cam.width; ++u) {
      const Eigen::Vector3d ray((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0);
      const double z = up.dot(face) / up.dot(ray);
      depth[std::size_t(v) * cam.width + u] = z > 0 && z < 3000 ? float(z) : 0.0f;
    }
  return noisy_image(
      cam, 0.5f, 7, [&](std::size_t i, const Eigen::Vector3d&) { return depth[i]; },
      [&](std::size_t i) { return depth[i] > 0; });
}

FitGeometry plate_fit_geometry(const PpfModel& model) {
  FitGeometry g;
  g.diameter = model.diameter;
  g.voxel_size = model.voxel_size;
  g.centroid = model_centroid(model.cloud);
  return g;
}

}  // namespace binpick::test
