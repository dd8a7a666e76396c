#include "host/eval/report/scene_view.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "host/core/error.hpp"

namespace binpick::eval {

std::optional<Eigen::Vector2d> SceneView::project(const Eigen::Vector3d& p) const {
  if (p.z() <= 1e-6) return std::nullopt;
  const Eigen::Vector3d q = K * p;
  return Eigen::Vector2d(q.x() / q.z(), q.y() / q.z());
}

SceneView load_scene_view(const Dataset& dataset, const ImageKey& key) {
  const auto it = dataset.images.find(key);
  if (it == dataset.images.end())
    throw InputError(fmt::format("dataset {} has no scene {} image {}", dataset.root.string(),
                                 key.scene_id, key.im_id));
  const auto& image = it->second;
  SceneView v;
  v.depth_raw = read_png16(image.files.depth(key.im_id));
  if (const auto gray = image.files.intensity(key.im_id); std::filesystem::exists(gray)) {
    v.gray = read_png8(gray);
    if (v.gray.width != v.depth_raw.width || v.gray.height != v.depth_raw.height)
      throw InputError(gray.string() + " differs in size from its depth image");
  }
  v.depth_scale = image.camera.depth_scale;
  v.K = image.camera.K;
  const double fx = v.K(0, 0), fy = v.K(1, 1), cx = v.K(0, 2), cy = v.K(1, 2);
  v.points.resize(v.depth_raw.pixels.size(), Eigen::Vector3f::Zero());
  for (std::uint32_t y = 0; y < v.depth_raw.height; ++y)
    for (std::uint32_t x = 0; x < v.depth_raw.width; ++x) {
      const std::size_t i = std::size_t(y) * v.depth_raw.width + x;
      const double z = v.depth_mm(i);
      if (z > 0) v.points[i] = Eigen::Vector3d((x - cx) * z / fx, (y - cy) * z / fy, z).cast<float>();
    }
  return v;
}

}  // namespace binpick::eval
