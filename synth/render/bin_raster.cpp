#include "synth/render/bin_raster.hpp"

#include <algorithm>
#include <cstring>

namespace binpick {
namespace {

constexpr vk::Format kIdFormat = vk::Format::eR32Uint;
constexpr vk::Format kNormalFormat = vk::Format::eR32G32B32A32Sfloat;
constexpr vk::Format kDepthFormat = vk::Format::eD32Sfloat;
// The atlas holds a 350-part bin's tiles (about 120 x 120 pixels each) in one batch.
constexpr std::uint32_t kAtlasWidth = 4096, kAtlasHeight = 2048;

constexpr std::uint32_t kVertexFloats = 6;    // position, normal
constexpr std::uint32_t kInstanceFloats = 12;  // 3 rows of [R | t]

vkrt::RasterSpec mesh_spec(const char* fragment_shader, std::vector<vk::Format> colors,
                           vk::Format depth, bool cull_back_faces) {
  const auto vec3 = vk::Format::eR32G32B32Sfloat, vec4 = vk::Format::eR32G32B32A32Sfloat;
  return {.vertex_shader = "bin_mesh.vert",
          .fragment_shader = fragment_shader,
          .color_formats = std::move(colors),
          .depth_format = depth,
          .vertex_bindings = {{.binding = 0, .stride = kVertexFloats * 4,
                               .inputRate = vk::VertexInputRate::eVertex},
                              {.binding = 1, .stride = kInstanceFloats * 4,
                               .inputRate = vk::VertexInputRate::eInstance}},
          .vertex_attributes = {{.location = 0, .binding = 0, .format = vec3, .offset = 0},
                                {.location = 1, .binding = 0, .format = vec3, .offset = 12},
                                {.location = 2, .binding = 1, .format = vec4, .offset = 0},
                                {.location = 3, .binding = 1, .format = vec4, .offset = 16},
                                {.location = 4, .binding = 1, .format = vec4, .offset = 32}},
          .push_constant_bytes = sizeof(MeshCamera),
          .cull = cull_back_faces ? vk::CullModeFlagBits::eBack : vk::CullModeFlagBits::eNone};
}

vkrt::Buffer filled(vkrt::Context& ctx, const void* data, std::size_t bytes, vk::BufferUsageFlags usage) {
  vkrt::Buffer b(ctx, bytes, usage);
  if (bytes) std::memcpy(b.mapped(), data, bytes);
  return b;
}

std::vector<float> interleaved_vertices(const Mesh& part) {
  std::vector<float> v;
  v.reserve(part.positions.size() * kVertexFloats);
  for (std::size_t i = 0; i < part.positions.size(); ++i)
    for (const auto& a : {part.positions[i], part.normals[i]}) v.insert(v.end(), {a.x(), a.y(), a.z()});
  return v;
}

constexpr auto kColorTarget = vk::ImageUsageFlagBits::eColorAttachment | vk::ImageUsageFlagBits::eTransferSrc;
constexpr auto kReadback = vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst;

}  // namespace

BinRaster::BinRaster(vkrt::Context& ctx, const Mesh& part, const RenderCamera& c,
                     bool cull_back_faces)
    : ctx_(ctx),
      camera_{float(c.width), float(c.height), float(c.fx), float(c.fy), float(c.cx), float(c.cy),
              float(c.near_mm), float(c.far_mm)},
      index_count_(std::uint32_t(part.triangles.size() * 3)),
      vertices_([&] {
        auto v = interleaved_vertices(part);
        return filled(ctx, v.data(), v.size() * 4, vk::BufferUsageFlagBits::eVertexBuffer);
      }()),
      indices_(filled(ctx, part.triangles.data(), part.triangles.size() * 12,
                      vk::BufferUsageFlagBits::eIndexBuffer)),
      scene_(ctx, mesh_spec("bin_mesh.frag", {kIdFormat, kNormalFormat}, kDepthFormat, cull_back_faces)),
      coverage_(ctx, mesh_spec("bin_part_id.frag", {kIdFormat}, vk::Format::eUndefined, cull_back_faces)),
      id_image_(ctx, c.width, c.height, kIdFormat, kColorTarget, vk::ImageAspectFlagBits::eColor),
      normal_image_(ctx, c.width, c.height, kNormalFormat, kColorTarget, vk::ImageAspectFlagBits::eColor),
      depth_image_(ctx, c.width, c.height, kDepthFormat,
                   vk::ImageUsageFlagBits::eDepthStencilAttachment | vk::ImageUsageFlagBits::eTransferSrc,
                   vk::ImageAspectFlagBits::eDepth),
      atlas_(ctx, std::max(kAtlasWidth, c.width), std::max(kAtlasHeight, c.height), kIdFormat,
             kColorTarget, vk::ImageAspectFlagBits::eColor),
      zbuffer_(ctx, std::size_t(c.width) * c.height * 4, kReadback),
      ids_(ctx, std::size_t(c.width) * c.height * 4, kReadback),
      raster_normals_(ctx, std::size_t(c.width) * c.height * 16, kReadback),
      atlas_ids_(ctx, std::size_t(atlas_.width()) * atlas_.height() * 4, kReadback) {
  scene_fb_ = scene_.framebuffer({&id_image_, &normal_image_, &depth_image_});
  atlas_fb_ = coverage_.framebuffer({&atlas_});
}

vkrt::Buffer BinRaster::instance_buffer(const std::vector<Eigen::Isometry3d>& part_to_camera) const {
  std::vector<float> rows;
  rows.reserve(part_to_camera.size() * kInstanceFloats);
  for (const auto& pose : part_to_camera)
    for (int r = 0; r < 3; ++r)
      for (int col = 0; col < 4; ++col) rows.push_back(float(pose.matrix()(r, col)));
  return filled(ctx_, rows.data(), rows.size() * 4, vk::BufferUsageFlagBits::eVertexBuffer);
}

void BinRaster::bind_mesh(const vk::raii::CommandBuffer& cmd, const vkrt::Buffer& instances) const {
  cmd.bindVertexBuffers(0, {vertices_.get(), instances.get()}, {vk::DeviceSize(0), vk::DeviceSize(0)});
  cmd.bindIndexBuffer(indices_.get(), 0, vk::IndexType::eUint32);
}

void BinRaster::copies_done(const vk::raii::CommandBuffer& cmd) {
  vk::MemoryBarrier barrier{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                            .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eHostRead};
  cmd.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer,
                      vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eHost, {},
                      barrier, {}, {});
}

void BinRaster::draw_scene(const vkrt::Buffer& instances, std::uint32_t count) {
  const std::uint32_t w = id_image_.width(), h = id_image_.height();
  ctx_.submit_and_wait(
      [&](const vk::raii::CommandBuffer& cmd) {
        scene_.begin(cmd, *scene_fb_, {{0, 0}, {w, h}}, &camera_);
        if (count > 0 && index_count_ > 0) {
          bind_mesh(cmd, instances);
          cmd.drawIndexed(index_count_, count, 0, 0, 0);
        }
        scene_.end(cmd);
        id_image_.record_copy_to(cmd, ids_.get(), 0, 0, w, h);
        normal_image_.record_copy_to(cmd, raster_normals_.get(), 0, 0, w, h);
        depth_image_.record_copy_to(cmd, zbuffer_.get(), 0, 0, w, h);
        copies_done(cmd);
      },
      "rendering the bin");
}

void BinRaster::draw_atlas(const vkrt::Buffer& instances, const AtlasBatch& batch) {
  if (batch.tiles.empty()) return;
  const std::uint32_t w = std::uint32_t(batch.width), h = std::uint32_t(batch.height);
  ctx_.submit_and_wait(
      [&](const vk::raii::CommandBuffer& cmd) {
        coverage_.begin(cmd, *atlas_fb_, {{0, 0}, {w, h}}, &camera_);
        bind_mesh(cmd, instances);
        for (const AtlasTile& t : batch.tiles) {
          // The whole image's viewport, shifted so the tile's image rectangle lands on its atlas
          // place: an integer shift, so the part covers exactly the pixels it covers in the image.
          cmd.setViewport(0, vk::Viewport{.x = float(t.atlas_x - t.image.x),
                                          .y = float(t.atlas_y - t.image.y),
                                          .width = camera_.width, .height = camera_.height,
                                          .minDepth = 0.0f, .maxDepth = 1.0f});
          cmd.setScissor(0, vk::Rect2D{{t.atlas_x, t.atlas_y},
                                       {std::uint32_t(t.image.w), std::uint32_t(t.image.h)}});
          cmd.drawIndexed(index_count_, 1, 0, 0, std::uint32_t(t.part));
        }
        coverage_.end(cmd);
        atlas_.record_copy_to(cmd, atlas_ids_.get(), 0, 0, w, h);
        copies_done(cmd);
      },
      "rendering the parts alone");
}

}  // namespace binpick
