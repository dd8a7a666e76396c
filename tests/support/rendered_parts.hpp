// Parts at known poses seen by a small depth camera, for detection tests that need a scene of
// exact geometry (which part is highest, which is beside it): the flat-region test, the coarse
// ranking of the highest points.
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "host/core/mesh.hpp"
#include "host/detect/scene/depth_to_points.hpp"
#include "host/detect/select/detection.hpp"
#include "host/eval/metrics/pose_error.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "host/train/ppf_model.hpp"

namespace binpick::test {

struct RenderedScene {
  DepthImage depth;
  bp_camera cam{};
  PointCloud cloud;  // the visible samples (the cloud path's input)
};

// Surface samples of each mesh moved by its pose, z-buffered into a 320 x 240 image (600 px)
// over a floor at floor_z; the samples that own a pixel are also the visible cloud.
RenderedScene render_parts(const std::vector<std::pair<Mesh, Eigen::Isometry3f>>& parts,
                           float floor_z);

// The built-in shaft (its model trained with the defaults), tilted, its origin at `at` (mm,
// camera frame), beside `other` at `other_pose`, over a floor a diameter beyond 600 mm: the
// hypothesis tests' scenes, where something else lies highest.
struct ShaftBeside {
  Model part;
  PpfModel model;
  Eigen::Isometry3f pose;
  RenderedScene scene;
  // A detection's error from the shaft's pose (its symmetries counted).
  eval::PoseError error_of(const Detection& d) const;
};
ShaftBeside shaft_beside(const Eigen::Vector3f& at, const Mesh& other,
                         const Eigen::Isometry3f& other_pose);

}  // namespace binpick::test
