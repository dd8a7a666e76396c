#include "host/detect/shared_scene.hpp"

#include <memory>

namespace binpick {

PreparedScene SharedScene::scene_for_model(ocl::Device& dev, DepthView depth,
                                           const bp_camera& cam, const ScenePrepOptions& opt) {
  const bool first = !prepared_;
  if (first) prepared_ = prepare_scene(dev, depth, cam, opt);
  PreparedScene scene = *prepared_;
  if (!first) scene.timings.clear();
  // The points are only read; the low-pass is rewritten by a model's region mask, or written
  // by it when the preparation left it out.
  scene.device = std::make_shared<DeviceScene>(*prepared_->device);
  scene.device->filtered = prepared_->has_lowpass
                               ? prepared_->device->filtered.clone(dev)
                               : ocl::Buffer<float>(dev, prepared_->device->filtered.size());
  return scene;
}

const BinFit* SharedScene::bin(const std::string& spec, double part_diameter) const {
  for (const auto& [key, fit] : bins_)
    if (key.first == spec && key.second == part_diameter) return &fit;
  return nullptr;
}

void SharedScene::keep_bin(const std::string& spec, double part_diameter, const BinFit& fit) {
  if (!bin(spec, part_diameter)) bins_.push_back({{spec, part_diameter}, fit});
}

}  // namespace binpick
