#include "synth/render/bin_raster.hpp"

#include <algorithm>
#include <cstring>

#include "host/core/error.hpp"

namespace binpick {
namespace {

constexpr vk::Format kIdFormat = vk::Format::eR32Uint;
constexpr vk::Format kNormalFormat = vk::Format::eR32G32B32A32Sfloat;
constexpr vk::Format kDepthFormat = vk::Format::eD32Sfloat;
// The atlas holds a 350-part bin's tiles (about 120 x 120 pixels each) in one batch.
constexpr std::uint32_t kAtlasWidth = 4096, kAtlasHeight = 2048;

constexpr std::uint32_t kVertexFloats = 6;     // position, normal
constexpr std::uint32_t kInstanceWords = 13;   // 3 rows of [R | t] (float), the id (uint)

vkrt::RasterSpec mesh_spec(const char* fragment_shader, std::vector<vk::Format> colors,
                           vk::Format depth, bool cull_back_faces) {
  const auto vec3 = vk::Format::eR32G32B32Sfloat, vec4 = vk::Format::eR32G32B32A32Sfloat;
  return {.vertex_shader = "bin_mesh.vert",
          .fragment_shader = fragment_shader,
          .color_formats = std::move(colors),
          .depth_format = depth,
          .vertex_bindings = {{.binding = 0, .stride = kVertexFloats * 4,
                               .inputRate = vk::VertexInputRate::eVertex},
                              {.binding = 1, .stride = kInstanceWords * 4,
                               .inputRate = vk::VertexInputRate::eInstance}},
          .vertex_attributes = {{.location = 0, .binding = 0, .format = vec3, .offset = 0},
                                {.location = 1, .binding = 0, .format = vec3, .offset = 12},
                                {.location = 2, .binding = 1, .format = vec4, .offset = 0},
                                {.location = 3, .binding = 1, .format = vec4, .offset = 16},
                                {.location = 4, .binding = 1, .format = vec4, .offset = 32},
                                {.location = 5, .binding = 1, .format = vk::Format::eR32Uint,
                                 .offset = 48}},
          .push_constant_bytes = sizeof(MeshCamera),
          .cull = cull_back_faces ? vk::CullModeFlagBits::eBack : vk::CullModeFlagBits::eNone};
}

vkrt::Buffer filled(vkrt::Context& ctx, const void* data, std::size_t bytes, vk::BufferUsageFlags usage) {
  vkrt::Buffer b(ctx, std::max<std::size_t>(bytes, 4), usage);
  if (bytes) std::memcpy(b.mapped(), data, bytes);
  return b;
}

constexpr auto kColorTarget = vk::ImageUsageFlagBits::eColorAttachment | vk::ImageUsageFlagBits::eTransferSrc;
constexpr auto kReadback = vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst;

}  // namespace

struct BinRaster::Packed {
  std::vector<float> vertices;
  std::vector<std::uint32_t> indices;
  std::vector<MeshRange> parts;
  std::optional<MeshRange> bin;

  MeshRange add(const Mesh& mesh, bool both_ways) {
    MeshRange r{std::uint32_t(indices.size()), 0, std::int32_t(vertices.size() / kVertexFloats)};
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
      for (const auto& a : {mesh.positions[i], mesh.normals[i]})
        vertices.insert(vertices.end(), {a.x(), a.y(), a.z()});
    for (const auto& t : mesh.triangles) indices.insert(indices.end(), t.begin(), t.end());
    if (both_ways)
      for (const auto& t : mesh.triangles) indices.insert(indices.end(), {t[0], t[2], t[1]});
    r.index_count = std::uint32_t(indices.size()) - r.first_index;
    return r;
  }
};

BinRaster::BinRaster(vkrt::Context& ctx, const std::vector<Mesh>& parts, const Mesh* bin,
                     bool bin_double_sided, const RenderCamera& camera, bool cull_back_faces)
    : BinRaster(ctx,
                [&] {
                  Packed p;
                  for (const Mesh& m : parts) p.parts.push_back(p.add(m, false));
                  if (bin) p.bin = p.add(*bin, bin_double_sided);
                  return p;
                }(),
                camera, cull_back_faces) {}

BinRaster::BinRaster(vkrt::Context& ctx, Packed packed, const RenderCamera& c, bool cull_back_faces)
    : ctx_(ctx),
      camera_{float(c.width), float(c.height), float(c.fx), float(c.fy), float(c.cx), float(c.cy),
              float(c.near_mm), float(c.far_mm)},
      parts_(std::move(packed.parts)),
      bin_(packed.bin),
      vertices_(filled(ctx, packed.vertices.data(), packed.vertices.size() * 4,
                       vk::BufferUsageFlagBits::eVertexBuffer)),
      indices_(filled(ctx, packed.indices.data(), packed.indices.size() * 4,
                      vk::BufferUsageFlagBits::eIndexBuffer)),
      scene_(ctx, mesh_spec("bin_mesh.frag", {kIdFormat, kNormalFormat}, kDepthFormat, cull_back_faces)),
      coverage_(ctx, mesh_spec("bin_part_id.frag", {kIdFormat}, kDepthFormat, cull_back_faces)),
      id_image_(ctx, c.width, c.height, kIdFormat, kColorTarget, vk::ImageAspectFlagBits::eColor),
      normal_image_(ctx, c.width, c.height, kNormalFormat, kColorTarget, vk::ImageAspectFlagBits::eColor),
      depth_image_(ctx, c.width, c.height, kDepthFormat,
                   vk::ImageUsageFlagBits::eDepthStencilAttachment | vk::ImageUsageFlagBits::eTransferSrc,
                   vk::ImageAspectFlagBits::eDepth),
      atlas_(ctx, std::max(kAtlasWidth, c.width), std::max(kAtlasHeight, c.height), kIdFormat,
             kColorTarget, vk::ImageAspectFlagBits::eColor),
      atlas_depth_(ctx, atlas_.width(), atlas_.height(), kDepthFormat,
                   vk::ImageUsageFlagBits::eDepthStencilAttachment | vk::ImageUsageFlagBits::eTransferSrc,
                   vk::ImageAspectFlagBits::eDepth),
      zbuffer_(ctx, std::size_t(c.width) * c.height * 4, kReadback),
      ids_(ctx, std::size_t(c.width) * c.height * 4, kReadback),
      raster_normals_(ctx, std::size_t(c.width) * c.height * 16, kReadback),
      atlas_ids_(ctx, std::size_t(atlas_.width()) * atlas_.height() * 4, kReadback),
      atlas_zbuffer_(ctx, std::size_t(atlas_.width()) * atlas_.height() * 4, kReadback) {
  scene_fb_ = scene_.framebuffer({&id_image_, &normal_image_, &depth_image_});
  atlas_fb_ = coverage_.framebuffer({&atlas_, &atlas_depth_});
}

RasterInstances BinRaster::instances(const std::vector<Eigen::Isometry3d>& part_to_camera,
                                     const std::vector<int>& kinds,
                                     const std::optional<Eigen::Isometry3d>& world_to_camera) const {
  if (kinds.size() != part_to_camera.size())
    throw InputError("render: " + std::to_string(kinds.size()) + " kinds for " +
                     std::to_string(part_to_camera.size()) + " parts");
  const bool with_bin = world_to_camera.has_value() && bin_.has_value();
  std::vector<std::uint32_t> first(parts_.size(), 0), count(parts_.size(), 0);
  std::vector<std::uint32_t> slot(kinds.size(), 0);
  for (const int k : kinds) {
    if (k < 0 || std::size_t(k) >= parts_.size())
      throw InputError("render: a part of kind " + std::to_string(k) + " of " +
                       std::to_string(parts_.size()));
    ++count[std::size_t(k)];
  }
  for (std::size_t k = 1; k < parts_.size(); ++k) first[k] = first[k - 1] + count[k - 1];

  std::vector<std::uint32_t> words((kinds.size() + (with_bin ? 1 : 0)) * kInstanceWords);
  const auto put = [&](std::size_t at, const Eigen::Isometry3d& pose, std::uint32_t id) {
    std::uint32_t* w = &words[at * kInstanceWords];
    for (int r = 0; r < 3; ++r)
      for (int col = 0; col < 4; ++col) {
        const float f = float(pose.matrix()(r, col));
        std::memcpy(w++, &f, 4);
      }
    *w = id;
  };
  std::vector<std::uint32_t> next = first;
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    slot[i] = next[std::size_t(kinds[i])]++;
    put(slot[i], part_to_camera[i], std::uint32_t(i) + 1u);
  }
  if (with_bin) put(kinds.size(), *world_to_camera, kStaticSurfaceId);
  return {filled(ctx_, words.data(), words.size() * 4, vk::BufferUsageFlagBits::eVertexBuffer),
          std::move(first), std::move(count), std::move(slot), kinds, with_bin};
}

void BinRaster::bind(const vk::raii::CommandBuffer& cmd, const vkrt::Buffer& instances) const {
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

void BinRaster::draw_scene(const RasterInstances& in) {
  const std::uint32_t w = id_image_.width(), h = id_image_.height();
  ctx_.submit_and_wait(
      [&](const vk::raii::CommandBuffer& cmd) {
        scene_.begin(cmd, *scene_fb_, {{0, 0}, {w, h}}, &camera_);
        bind(cmd, in.buffer);
        for (std::size_t k = 0; k < parts_.size(); ++k)
          if (in.count[k] > 0 && parts_[k].index_count > 0)
            cmd.drawIndexed(parts_[k].index_count, in.count[k], parts_[k].first_index,
                            parts_[k].vertex_offset, in.first[k]);
        if (in.bin)
          cmd.drawIndexed(bin_->index_count, 1, bin_->first_index, bin_->vertex_offset,
                          std::uint32_t(in.kinds.size()));
        scene_.end(cmd);
        id_image_.record_copy_to(cmd, ids_.get(), 0, 0, w, h);
        normal_image_.record_copy_to(cmd, raster_normals_.get(), 0, 0, w, h);
        depth_image_.record_copy_to(cmd, zbuffer_.get(), 0, 0, w, h);
        copies_done(cmd);
      },
      "rendering the bin");
}

void BinRaster::draw_atlas(const RasterInstances& in, const AtlasBatch& batch, bool with_depth) {
  if (batch.tiles.empty()) return;
  const std::uint32_t w = std::uint32_t(batch.width), h = std::uint32_t(batch.height);
  ctx_.submit_and_wait(
      [&](const vk::raii::CommandBuffer& cmd) {
        coverage_.begin(cmd, *atlas_fb_, {{0, 0}, {w, h}}, &camera_);
        bind(cmd, in.buffer);
        for (const AtlasTile& t : batch.tiles) {
          // The whole image's viewport, shifted so the tile's image rectangle lands on its atlas
          // place: an integer shift, so the part covers exactly the pixels it covers in the image.
          cmd.setViewport(0, vk::Viewport{.x = float(t.atlas_x - t.image.x),
                                          .y = float(t.atlas_y - t.image.y),
                                          .width = camera_.width, .height = camera_.height,
                                          .minDepth = 0.0f, .maxDepth = 1.0f});
          cmd.setScissor(0, vk::Rect2D{{t.atlas_x, t.atlas_y},
                                       {std::uint32_t(t.image.w), std::uint32_t(t.image.h)}});
          const MeshRange& m = parts_[std::size_t(in.kinds[std::size_t(t.part)])];
          cmd.drawIndexed(m.index_count, 1, m.first_index, m.vertex_offset,
                          in.slot[std::size_t(t.part)]);
        }
        coverage_.end(cmd);
        atlas_.record_copy_to(cmd, atlas_ids_.get(), 0, 0, w, h);
        if (with_depth) atlas_depth_.record_copy_to(cmd, atlas_zbuffer_.get(), 0, 0, w, h);
        copies_done(cmd);
      },
      "rendering the parts alone");
}

}  // namespace binpick
