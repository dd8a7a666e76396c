// Each part drawn alone (BOP's "object rendered in its ground-truth pose", calc_gt_info.py):
// the image pixels it covers and the model's depth there, nearest surface of the part only.
// The renderer gets them from the atlas pass (bin_atlas.hpp, one tile a part, with a depth
// attachment); part_silhouette_reference rasterises one part in plain C++ to check it.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "host/core/mesh.hpp"
#include "synth/render/bin_atlas.hpp"
#include "synth/render/bin_camera.hpp"

namespace binpick {

// Pixels are row-major indices into the image (each once, in increasing order), depth_mm the
// camera z (mm, > 0) of the part's nearest surface there, in the same order.
struct PartSilhouette {
  std::vector<std::uint32_t> pixels;
  std::vector<float> depth_mm;
};

// From one atlas batch as read back: ids (part + 1, 0 none) and z-buffer values (near -> 0,
// far -> 1), both batch.width x batch.height row-major. Fills out[tile.part] for every tile
// (out must hold every part); z is turned into depth as bin_gbuffer.comp does (float).
void silhouettes_from_atlas(const std::uint32_t* ids, const float* zbuffer, const AtlasBatch& batch,
                            const RenderCamera& camera, std::vector<PartSilhouette>& out);

// Reference: the part rasterised alone in plain C++ with the renderer's conventions (pixel
// centres at integer (u, v), 1/256-pixel vertex snapping, top-left fill rule, back faces culled
// when asked, depth interpolated as 1/z across the screen). Triangles with a corner outside
// [near, far] are skipped (the renderer clips them): keep reference parts inside the frustum's
// depth range. Coverage can differ from the GPU's only for pixel centres on a triangle edge.
PartSilhouette part_silhouette_reference(const Mesh& part, const Eigen::Isometry3d& part_to_camera,
                                         const RenderCamera& camera, bool cull_back_faces);

}  // namespace binpick
