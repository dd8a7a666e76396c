#include "host/detect/pick/pick_clearance.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "host/detect/scene/scene_crop.hpp"

namespace binpick {

bp_pick_candidate pick_candidate(const std::vector<GripperSolid>& solids,
                                 const Eigen::Isometry3d& grasp_in_camera, const bp_camera& cam,
                                 float tolerance, float cap) {
  if (solids.empty() || solids.size() > BP_PICK_MAX_SOLIDS)
    throw std::logic_error("pick_candidate: 1 to 3 solids");
  bp_pick_candidate c{};
  const Eigen::Matrix3d to_grasp = grasp_in_camera.linear().transpose();
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) c.rot[3 * r + k] = float(to_grasp(r, k));
  for (int k = 0; k < 3; ++k) c.origin[k] = float(grasp_in_camera.translation()[k]);
  // The window: the pixels of a sphere about the solids' middle holding them and cap around.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e30), hi = -lo;
  for (std::size_t k = 0; k < solids.size(); ++k) {
    const GripperSolid& s = solids[k];
    c.shape[k] = s.shape == GripperSolid::Shape::cylinder ? BP_PICK_CYLINDER : BP_PICK_BOX;
    Eigen::Vector3d half = s.half;
    if (s.shape == GripperSolid::Shape::cylinder) half.y() = half.x();
    for (int i = 0; i < 3; ++i) {
      c.centre[3 * k + i] = float(s.centre[i]);
      c.extent[3 * k + i] = float(s.half[i]);
    }
    lo = lo.cwiseMin(s.centre - half);
    hi = hi.cwiseMax(s.centre + half);
  }
  c.solids = std::uint32_t(solids.size());
  c.tolerance = tolerance;
  c.cap = cap;
  CropOptions sphere;
  sphere.centre = (grasp_in_camera * (0.5 * (lo + hi))).cast<float>();
  sphere.radius = float(0.5 * (hi - lo).norm()) + cap + tolerance;
  const auto rect = crop_pixel_rect(cam, sphere);
  for (int k = 0; k < 4; ++k) c.rect[k] = rect[std::size_t(k)];
  return c;
}

std::vector<bp_pick_result> pick_clearance(ocl::Device& dev, const ocl::Buffer<float>& points,
                                           const bp_camera& cam,
                                           const std::vector<bp_pick_candidate>& candidates) {
  if (points.size() != 4 * std::size_t(cam.width) * cam.height)
    throw std::logic_error("pick_clearance: the point image does not match the camera");
  if (candidates.empty()) return {};
  const ocl::Buffer<bp_pick_candidate> in(dev, std::span<const bp_pick_candidate>(candidates),
                                          CL_MEM_READ_ONLY);
  ocl::Buffer<bp_pick_result> out(dev, candidates.size());
  cl::Kernel kernel = dev.kernel("pick_clearance.cl", "pick_clearance");
  ocl::launch_tasks(dev, kernel, candidates.size(), points, cl_uint(cam.width), in,
                    cl_uint(candidates.size()), out);
  return out.read(dev);
}

std::vector<bp_pick_result> pick_clearance_reference(const std::vector<float>& points,
                                                     const bp_camera& cam,
                                                     const std::vector<bp_pick_candidate>& candidates) {
  std::vector<bp_pick_result> results;
  for (const bp_pick_candidate& c : candidates) {
    bp_pick_result r{0, c.cap};
    for (std::uint32_t v = c.rect[1]; v < c.rect[3]; ++v)
      for (std::uint32_t u = c.rect[0]; u < c.rect[2]; ++u) {
        const float* p = &points[4 * (std::size_t(v) * cam.width + u)];
        if (p[3] == 0.0f) continue;
        float qz;
        const float d = bp_pick_distance(&c, p[0], p[1], p[2], &qz);
        if (d < -c.tolerance)
          ++r.colliding;
        else if (qz < -c.tolerance && d < r.clearance)
          r.clearance = d > 0.0f ? d : 0.0f;
      }
    results.push_back(r);
  }
  return results;
}

}  // namespace binpick
