// Parts at known poses seen by a small depth camera, for detection tests that need a scene of
// exact geometry (which part is highest, which is beside it): the flat-region test, the coarse
// ranking of the highest points.
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "host/core/mesh.hpp"
#include "host/detect/scene/depth_to_points.hpp"

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

}  // namespace binpick::test
