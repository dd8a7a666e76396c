// Writes one synthetic bin as one BOP scene (image id 0): depth, gray, cloud, masks and the
// scene JSON files (docs/formats.md).
#pragma once

#include <filesystem>
#include <vector>

#include <Eigen/Geometry>

#include "synth/render/bin_renderer.hpp"

namespace binpick {

struct BinRecord {
  const RenderedBin& render;
  // Each part drawn alone with bop_toolkit_sampling(camera) (BinRenderer::silhouettes), one per
  // part: scene_gt_info.json and the masks come from these, as calc_gt_info.py renders them.
  const std::vector<PartSilhouette>& silhouettes;
  const RenderCamera& camera;
  const Eigen::Isometry3d& world_to_camera;
  const std::vector<Eigen::Isometry3d>& part_to_camera;  // mm, one per part, same order as render
  const std::vector<int>& obj_ids;                       // per part, its BOP obj_id
  double depth_scale = 0.1;                              // mm per depth PNG unit
  bool write_cloud = true;
  bool write_masks = false;
};

// Writes into scene_dir (which must exist and is expected to be a temporary directory that the
// caller renames into place once everything is written).
void write_bop_scene(const std::filesystem::path& scene_dir, const BinRecord& bin);

}  // namespace binpick
