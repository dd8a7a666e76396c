// The raster half of the bin renderer: the part mesh in vertex buffers, the two raster
// pipelines (scene: id + normal + depth; coverage: id only, each part alone in an atlas tile),
// their attachments, and host-visible copies of what they drew for the compute passes.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "host/core/mesh.hpp"
#include "synth/render/bin_atlas.hpp"
#include "synth/render/bin_camera.hpp"
#include "host/runtime/vk/vk_buffer.hpp"
#include "host/runtime/vk/vk_image.hpp"
#include "host/runtime/vk/vk_raster.hpp"

namespace binpick {

// The push constant block of bin_mesh.vert.
struct MeshCamera {
  float width, height, fx, fy, cx, cy, near_mm, far_mm;
};

class BinRaster {
 public:
  // part must have per-vertex normals and triangles. Back faces (clockwise in the image) are
  // culled when asked: a quarter less work for a closed mesh, holes in an open one.
  BinRaster(vkrt::Context& ctx, const Mesh& part, const RenderCamera& camera, bool cull_back_faces);

  // Per-instance vertex data for the poses: 3 rows of [R | t] a part, float.
  vkrt::Buffer instance_buffer(const std::vector<Eigen::Isometry3d>& part_to_camera) const;

  // Draws every instance into the scene attachments and copies them into zbuffer(), ids() and
  // raster_normals().
  void draw_scene(const vkrt::Buffer& instances, std::uint32_t count);
  const vkrt::Buffer& zbuffer() const { return zbuffer_; }
  const vkrt::Buffer& ids() const { return ids_; }
  const vkrt::Buffer& raster_normals() const { return raster_normals_; }

  // Draws each tile's part alone into its atlas tile and copies the batch's region
  // (batch.width x batch.height, row-major) into atlas_ids().
  void draw_atlas(const vkrt::Buffer& instances, const AtlasBatch& batch);
  const vkrt::Buffer& atlas_ids() const { return atlas_ids_; }
  int atlas_width() const { return int(atlas_.width()); }
  int atlas_height() const { return int(atlas_.height()); }

 private:
  void bind_mesh(const vk::raii::CommandBuffer& cmd, const vkrt::Buffer& instances) const;
  // Transfer writes of the copies, before compute shaders and the host read them.
  static void copies_done(const vk::raii::CommandBuffer& cmd);

  vkrt::Context& ctx_;
  MeshCamera camera_;
  std::uint32_t index_count_;
  vkrt::Buffer vertices_, indices_;
  vkrt::RasterProgram scene_, coverage_;
  vkrt::Image id_image_, normal_image_, depth_image_, atlas_;
  vk::raii::Framebuffer scene_fb_{nullptr}, atlas_fb_{nullptr};
  vkrt::Buffer zbuffer_, ids_, raster_normals_, atlas_ids_;
};

}  // namespace binpick
