// The model rendered alone at a pose with an image's intrinsics, as BOP's VSD needs it (the
// toolkit's renderer.render_object(obj_id, R, t, fx, fy, cx, cy)["depth"]): binpick's Vulkan
// renderer draws each requested (obj_id, pose) into its own atlas tile in one pass
// (BinRenderer::silhouettes), so an image's estimates and ground truths cost one render.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <tuple>
#include <vector>

#include <Eigen/Core>

#include "host/core/mesh.hpp"
#include "host/eval/metrics/bop_pose_error.hpp"
#include "synth/render/part_silhouette.hpp"

namespace binpick {
class BinRenderer;
}

namespace binpick::eval {

// The clipping planes of the depth renders, mm: surfaces nearer than 10 mm or farther than
// 10 m are not drawn (binpick's bins lie at about 1 m, BOP's datasets within a few).
inline constexpr double kVsdNearMm = 10, kVsdFarMm = 10'000;

struct PosedObject {
  int obj_id = 1;
  RigidPose pose;  // model -> camera, mm
};

class ModelDepthRenderer {
 public:
  // meshes by obj_id, with triangles and per-vertex normals (load_model gives both). Nothing is
  // built until the first render.
  explicit ModelDepthRenderer(std::map<int, Mesh> meshes);
  ~ModelDepthRenderer();
  ModelDepthRenderer(const ModelDepthRenderer&) = delete;
  ModelDepthRenderer& operator=(const ModelDepthRenderer&) = delete;

  // Each object drawn alone in a width x height image with intrinsics K (skew ignored) and the
  // toolkit's pixel centres (bin_camera.hpp: bop_toolkit_sampling): its pixels and depth there (the nearest surface, back faces included, as the toolkit's
  // renderers draw). The renderer of the last camera is kept (building one compiles shaders;
  // each holds image-sized buffers, so datasets with many cameras do not pile them up).
  // InputError for an obj_id without a mesh.
  std::vector<PartSilhouette> render(const Eigen::Matrix3d& K, std::uint32_t width,
                                     std::uint32_t height, const std::vector<PosedObject>& objects);

 private:
  using CameraKey = std::tuple<std::uint32_t, std::uint32_t, double, double, double, double>;
  std::vector<Mesh> meshes_;
  std::map<int, int> kind_of_;  // obj_id -> index into meshes_
  CameraKey camera_{};
  std::unique_ptr<BinRenderer> renderer_;
};

}  // namespace binpick::eval
