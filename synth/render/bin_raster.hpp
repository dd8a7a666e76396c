// The raster half of the bin renderer: the meshes (each kind of part, and the bin) in one
// vertex and one index buffer, the two raster pipelines (scene: id + normal + depth; coverage:
// id + depth, each part alone in an atlas tile), their attachments, and host-visible copies of what
// they drew for the compute passes.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "host/core/mesh.hpp"
#include "synth/render/bin_atlas.hpp"
#include "synth/render/bin_camera.hpp"
#include "synth/render/bin_gbuffer.hpp"
#include "host/runtime/vk/vk_buffer.hpp"
#include "host/runtime/vk/vk_image.hpp"
#include "host/runtime/vk/vk_raster.hpp"

namespace binpick {

// The push constant block of bin_mesh.vert.
struct MeshCamera {
  float width, height, fx, fy, cx, cy, near_mm, far_mm;
};

// The instances of one render: per-instance data grouped by mesh, so each mesh is one
// instanced draw.
struct RasterInstances {
  vkrt::Buffer buffer;                     // 3 rows of [R | t] (float) and the id, an instance
  std::vector<std::uint32_t> first, count;  // per part mesh: its instances in the buffer
  std::vector<std::uint32_t> slot;          // per part: its instance in the buffer
  std::vector<int> kinds;                   // per part: its mesh
  bool bin = false;                         // the bin is the buffer's last instance
};

class BinRaster {
 public:
  // parts: one mesh a kind of part, with per-vertex normals and triangles. bin: the static
  // mesh (world frame) or none; double-sided bins get each triangle twice, once each way
  // round. Back faces (clockwise in the image) are culled when asked: a quarter less work for
  // closed meshes, holes in open ones.
  BinRaster(vkrt::Context& ctx, const std::vector<Mesh>& parts, const Mesh* bin,
            bool bin_double_sided, const RenderCamera& camera, bool cull_back_faces);

  // The instances: kinds[i] is part i's mesh; the bin is added when `world_to_camera` is given
  // and there is a bin mesh.
  RasterInstances instances(const std::vector<Eigen::Isometry3d>& part_to_camera,
                            const std::vector<int>& kinds,
                            const std::optional<Eigen::Isometry3d>& world_to_camera) const;

  // Draws every instance into the scene attachments and copies them into zbuffer(), ids() and
  // raster_normals().
  void draw_scene(const RasterInstances& instances);
  const vkrt::Buffer& zbuffer() const { return zbuffer_; }
  const vkrt::Buffer& ids() const { return ids_; }
  const vkrt::Buffer& raster_normals() const { return raster_normals_; }

  // Draws each tile's part alone into its atlas tile (with a depth test: the part's nearest
  // surface) and copies the batch's region (batch.width x batch.height, row-major) into
  // atlas_ids() and, with_depth, its z-buffer values into atlas_zbuffer().
  void draw_atlas(const RasterInstances& instances, const AtlasBatch& batch, bool with_depth = false);
  const vkrt::Buffer& atlas_ids() const { return atlas_ids_; }
  const vkrt::Buffer& atlas_zbuffer() const { return atlas_zbuffer_; }
  int atlas_width() const { return int(atlas_.width()); }
  int atlas_height() const { return int(atlas_.height()); }

 private:
  struct MeshRange {
    std::uint32_t first_index = 0, index_count = 0;
    std::int32_t vertex_offset = 0;
  };
  struct Packed;  // the meshes in one vertex and one index array
  BinRaster(vkrt::Context& ctx, Packed packed, const RenderCamera& camera, bool cull_back_faces);
  void bind(const vk::raii::CommandBuffer& cmd, const vkrt::Buffer& instances) const;
  // Transfer writes of the copies, before compute shaders and the host read them.
  static void copies_done(const vk::raii::CommandBuffer& cmd);

  vkrt::Context& ctx_;
  MeshCamera camera_;
  std::vector<MeshRange> parts_;
  std::optional<MeshRange> bin_;
  vkrt::Buffer vertices_, indices_;
  vkrt::RasterProgram scene_, coverage_;
  vkrt::Image id_image_, normal_image_, depth_image_, atlas_, atlas_depth_;
  vk::raii::Framebuffer scene_fb_{nullptr}, atlas_fb_{nullptr};
  vkrt::Buffer zbuffer_, ids_, raster_normals_, atlas_ids_, atlas_zbuffer_;
};

}  // namespace binpick
