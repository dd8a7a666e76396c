// One Gauss-Newton step's sums and the verification counts of many poses against a point image
// (kernels/pose_fit.cl; kernels/pose_fit_shared.h says what is counted). pose_refine.hpp
// drives it: ICP iterations, then the verified score.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "host/core/mesh.hpp"
#include "host/detect/scene/depth_to_points.hpp"
#include "host/detect/refine/model_patches.hpp"
#include "host/runtime/cl/cl_buffer.hpp"
#include "kernels/binpick_shared.h"
#include "kernels/pose_fit_shared.h"

namespace binpick {

// The model's points and normals on the device, uploaded once per detector.
struct DeviceFitModel {
  ocl::Buffer<cl_float4> points, normals;
  std::uint32_t size = 0;
};
DeviceFitModel upload_fit_model(ocl::Device& dev, const PointCloud& model);

// The mean of the model's points: the point poses are compared and turned about.
Eigen::Vector3d model_centroid(const PointCloud& model);

// A pose's sums in double: the normal equations of the step and the points per class.
struct FitSums {
  Eigen::Matrix<double, 6, 6> jtj = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> jtr = Eigen::Matrix<double, 6, 1>::Zero();
  double cost = 0;
  double agreement = 0;  // sum over inliers of 1 - (r / tolerance)^2
  std::array<std::uint32_t, BP_FIT_CLASSES> count{};  // indexed by BP_FIT_HIDDEN ...
  std::uint32_t used = 0;
  std::uint32_t outline_continue = 0, outline_step = 0;  // outline cells (pose_fit_shared.h)
  // With bp_pose_fit::residuals: one per model point, NaN where it gives no ICP term, and each
  // model point's class (BP_FIT_HIDDEN ...; hidden also where it faces away or falls outside).
  std::vector<float> residuals;
  std::vector<std::uint8_t> classes;

  std::uint32_t visible() const;  // all but hidden
};

// A pose to fit, with the z-buffer grid laid over where the posed model can project: a square
// around the projected centroid, wide enough for the model at its nearest, in cells about 1.5
// model voxels wide (so that every cell a surface crosses holds one of its points).
struct FitGeometry {
  float diameter = 0, voxel_size = 0;  // mm
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // model frame
  ModelPatches patches;  // of the fit model's points; none (count 0): no patch bias
  // The fit model's points and normals (model frame) for the ray spread, rival and seen area;
  // empty: none of them.
  std::vector<Eigen::Vector3f> points, normals;
  double mean_area = 0;  // the seen area's unit (seen_area.hpp); 0: off
};
struct FitThresholds {
  float gate = 0, tolerance = 0, slack = 0;  // mm
  float outline = 0;  // mm, the outline's tolerance; 0: no outline
  bool residuals = false;  // read back each model point's residual (the patch bias)
  float near_gate = 0;     // mm, pose_fit_shared.h (bp_near_gate); 0: off
};
// The cosine between a posed model point's normal nq and the ray from the point q (camera
// frame) back to the camera: > 0 where the point faces the camera.
inline double ray_cosine(const Eigen::Vector3d& q, const Eigen::Vector3d& nq) {
  return -nq.dot(q) / (q.norm() * nq.norm());
}
// The z-buffer's slack for a tolerance: the cell is about 1.5 voxels wide, so a sloped surface
// spans about that much depth in it, while a surface hidden behind the part's near side lies
// farther back.
inline float zbuffer_slack(const FitGeometry& g, float tolerance) {
  return std::max(2.0f * g.voxel_size, tolerance);
}
bp_pose_fit make_pose_fit(const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                          const bp_camera& cam, const FitGeometry& geometry,
                          const FitThresholds& thresholds);

// Routine: the sums of every fit. points: the scene's float4 point image on dev (xyz mm, w = 1
// where there is data), of the camera's size.
std::vector<FitSums> pose_fit_sums(ocl::Device& dev, const ocl::Buffer<float>& points,
                                   const bp_camera& cam, const DeviceFitModel& model,
                                   const std::vector<bp_pose_fit>& fits);
// Reference: the same classification (the shared functions), sums in double per point.
std::vector<FitSums> pose_fit_sums_reference(const PointImage& points, const bp_camera& cam,
                                             const PointCloud& model,
                                             const std::vector<bp_pose_fit>& fits);

}  // namespace binpick
