#include "host/eval/metrics/vsd_rendering.hpp"

#include <string>

#include <Eigen/Geometry>

#include "host/core/error.hpp"
#include "synth/render/bin_renderer.hpp"

namespace binpick::eval {

ModelDepthRenderer::ModelDepthRenderer(std::map<int, Mesh> meshes) {
  for (auto& [obj_id, mesh] : meshes) {
    kind_of_[obj_id] = int(meshes_.size());
    meshes_.push_back(std::move(mesh));
  }
}

ModelDepthRenderer::~ModelDepthRenderer() = default;

std::vector<PartSilhouette> ModelDepthRenderer::render(const Eigen::Matrix3d& K,
                                                       std::uint32_t width, std::uint32_t height,
                                                       const std::vector<PosedObject>& objects) {
  RenderScene scene;
  for (const auto& o : objects) {
    const auto kind = kind_of_.find(o.obj_id);
    if (kind == kind_of_.end())
      throw InputError("VSD: no model to render obj_id " + std::to_string(o.obj_id));
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = o.pose.R;
    pose.translation() = o.pose.t;
    scene.part_to_camera.push_back(pose);
    scene.kinds.push_back(kind->second);
  }
  if (objects.empty()) return {};
  const CameraKey key{width, height, K(0, 0), K(1, 1), K(0, 2), K(1, 2)};
  if (!renderer_ || key != camera_) {
    // Pixel centres as the toolkit's renderers place them (bin_camera.hpp), so that its VSD
    // and binpick's compare the same pixels.
    const RenderCamera camera = bop_toolkit_sampling(
        {width, height, K(0, 0), K(1, 1), K(0, 2), K(1, 2), kVsdNearMm, kVsdFarMm});
    renderer_.reset();  // first free the old one's buffers
    // Back faces are drawn: the toolkit's renderers do not cull, which matters for open meshes.
    renderer_ = std::make_unique<BinRenderer>(meshes_, nullptr, camera, false);
    camera_ = key;
  }
  return renderer_->silhouettes(scene);
}

}  // namespace binpick::eval
