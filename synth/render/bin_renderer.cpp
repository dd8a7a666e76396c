#include "synth/render/bin_renderer.hpp"

#include <chrono>
#include <cmath>
#include <string>

#include "host/core/error.hpp"
#include "synth/render/bin_atlas.hpp"
#include "synth/render/bin_coverage.hpp"
#include "synth/render/bin_gbuffer.hpp"
#include "synth/render/bin_raster.hpp"

namespace binpick {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::vector<Mesh> checked_parts(const std::vector<Mesh>& parts);

Mesh checked_part(const Mesh& part) {
  if (part.triangles.empty()) throw InputError("cannot render a part mesh without triangles");
  for (const auto& t : part.triangles)
    for (std::uint32_t i : t)
      if (i >= part.positions.size()) throw InputError("part mesh has a triangle index out of range");
  if (part.normals.size() != part.positions.size())
    throw InputError("part mesh has " + std::to_string(part.normals.size()) + " normals for " +
                     std::to_string(part.positions.size()) +
                     " vertices (compute_crease_normals gives a mesh its normals)");
  return part;
}

std::vector<Mesh> checked_parts(const std::vector<Mesh>& parts) {
  if (parts.empty()) throw InputError("cannot render a bin without a part mesh");
  std::vector<Mesh> out;
  for (const Mesh& m : parts) out.push_back(checked_part(m));
  return out;
}

void check_poses(const std::vector<Eigen::Isometry3d>& poses) {
  for (std::size_t i = 0; i < poses.size(); ++i)
    if (!poses[i].matrix().allFinite())
      throw InputError("pose of part " + std::to_string(i) + " is not finite");
}

std::vector<std::array<int, 4>> bop_bboxes(const PartPixels& parts) {
  std::vector<std::array<int, 4>> out;
  out.reserve(parts.box.size());
  for (const PixelBox& b : parts.box) out.push_back(bop_bbox(b));
  return out;
}

}  // namespace

struct BinRenderer::Device {
  vkrt::Context& ctx;
  BinRaster raster;
  GBufferStage gbuffer;
  CoverageStage coverage;
  Device(vkrt::Context& c, const std::vector<Mesh>& parts, const BinModel* bin,
         const RenderCamera& camera, bool cull)
      : ctx(c),
        raster(c, parts, bin ? &bin->mesh : nullptr, bin && bin->double_sided, camera, cull),
        gbuffer(c, camera.width, camera.height),
        coverage(c) {}
};

BinRenderer::BinRenderer(const Mesh& part, const RenderCamera& camera, bool cull_back_faces)
    : BinRenderer(part, camera, cull_back_faces, vkrt::Context::shared()) {}

BinRenderer::BinRenderer(const Mesh& part, const RenderCamera& camera, bool cull_back_faces,
                         vkrt::Context& ctx)
    : BinRenderer(std::vector<Mesh>{part}, nullptr, camera, cull_back_faces, ctx) {}

BinRenderer::BinRenderer(const std::vector<Mesh>& parts, const BinModel* bin,
                         const RenderCamera& camera, bool cull_back_faces)
    : BinRenderer(parts, bin, camera, cull_back_faces, vkrt::Context::shared()) {}

BinRenderer::BinRenderer(const std::vector<Mesh>& parts, const BinModel* bin,
                         const RenderCamera& camera, bool cull_back_faces, vkrt::Context& ctx)
    : camera_(camera), parts_(checked_parts(parts)) {
  check_camera(camera);
  if (bin && bin->mesh.normals.size() != bin->mesh.positions.size())
    throw InputError("the bin mesh needs per-vertex normals");
  device_ = std::make_unique<Device>(ctx, parts_, bin, camera_, cull_back_faces);
}

BinRenderer::~BinRenderer() = default;

RenderedBin BinRenderer::render(const std::vector<Eigen::Isometry3d>& part_to_camera,
                                const RenderOptions& options) {
  return render_scene(RenderScene{part_to_camera, {}, std::nullopt}, options);
}

RenderedBin BinRenderer::render_scene(const RenderScene& scene, const RenderOptions& options) {
  const auto& part_to_camera = scene.part_to_camera;
  check_poses(part_to_camera);
  if (scene.world_to_camera && !scene.world_to_camera->matrix().allFinite())
    throw InputError("the bin's pose is not finite");
  const auto parts = std::uint32_t(part_to_camera.size());
  const std::vector<int> kinds = scene.kinds.empty() ? std::vector<int>(parts, 0) : scene.kinds;
  Device& d = *device_;
  timings_ = {};

  auto start = Clock::now();
  const RasterInstances instances =
      d.raster.instances(part_to_camera, kinds, scene.world_to_camera);
  d.raster.draw_scene(instances);
  timings_.raster_ms = ms_since(start);

  start = Clock::now();
  PartPixelBuffers visible(d.ctx, parts);
  d.gbuffer.run(d.raster.zbuffer(), d.raster.ids(), d.raster.raster_normals(), visible,
                gbuffer_params(camera_, options.noise_sigma_mm, options.seed, parts));
  timings_.compute_ms = ms_since(start);

  start = Clock::now();
  GBufferOutput images = d.gbuffer.read();
  const PartPixels seen = visible.read();
  RenderedBin out{.width = camera_.width,
                  .height = camera_.height,
                  .depth_mm = std::move(images.depth_mm),
                  .gray = std::move(images.gray),
                  .points = std::move(images.points),
                  .normals = std::move(images.normals),
                  .instance = std::move(images.instance),
                  .px_visible = seen.count,
                  .px_all = {},
                  .bbox_visible = bop_bboxes(seen),
                  .bbox_all = {},
                  .silhouettes = {}};
  timings_.readback_ms = ms_since(start);

  if (!options.count_unoccluded) {
    if (options.silhouettes) throw InputError("render: silhouettes need count_unoccluded");
    return out;
  }
  start = Clock::now();
  const std::vector<PixelRect> rects = part_rects(scene, kinds);
  PartPixelBuffers alone(d.ctx, parts);
  std::vector<std::array<int, 2>> shifts(parts, {0, 0});
  if (options.silhouettes) out.silhouettes.assign(parts, {});
  for (const AtlasBatch& batch : pack_atlas(rects, d.raster.atlas_width(), d.raster.atlas_height())) {
    d.raster.draw_atlas(instances, batch, options.silhouettes);
    if (options.silhouettes) {
      const auto silhouettes = Clock::now();
      silhouettes_from_atlas(static_cast<const std::uint32_t*>(d.raster.atlas_ids().mapped()),
                             static_cast<const float*>(d.raster.atlas_zbuffer().mapped()), batch,
                             camera_, out.silhouettes);
      timings_.silhouettes_ms += ms_since(silhouettes);
    }
    for (const AtlasTile& t : batch.tiles) shifts[t.part] = {t.image.x - t.atlas_x, t.image.y - t.atlas_y};
    const auto shift_buffer = vkrt::Buffer::from(d.ctx, std::span<const std::array<int, 2>>(shifts));
    d.coverage.run(d.raster.atlas_ids(), shift_buffer, alone,
                   {std::uint32_t(batch.width), std::uint32_t(batch.height), parts});
  }
  const PartPixels all = alone.read();
  out.px_all = all.count;
  out.bbox_all = bop_bboxes(all);
  timings_.coverage_ms = ms_since(start);
  return out;
}

std::vector<PixelRect> BinRenderer::part_rects(const RenderScene& scene,
                                               const std::vector<int>& kinds) const {
  std::vector<PixelRect> rects(scene.part_to_camera.size());
  for (std::size_t i = 0; i < rects.size(); ++i)
    rects[i] = projected_rect(parts_[std::size_t(kinds[i])], scene.part_to_camera[i], camera_);
  return rects;
}

std::vector<PartSilhouette> BinRenderer::silhouettes(const RenderScene& scene) {
  check_poses(scene.part_to_camera);
  if (scene.part_to_camera.empty()) return {};
  const std::vector<int> kinds =
      scene.kinds.empty() ? std::vector<int>(scene.part_to_camera.size(), 0) : scene.kinds;
  Device& d = *device_;
  timings_ = {};
  const auto start = Clock::now();
  const RasterInstances instances = d.raster.instances(scene.part_to_camera, kinds, std::nullopt);
  std::vector<PartSilhouette> out(scene.part_to_camera.size());
  for (const AtlasBatch& batch :
       pack_atlas(part_rects(scene, kinds), d.raster.atlas_width(), d.raster.atlas_height())) {
    d.raster.draw_atlas(instances, batch, true);
    silhouettes_from_atlas(static_cast<const std::uint32_t*>(d.raster.atlas_ids().mapped()),
                           static_cast<const float*>(d.raster.atlas_zbuffer().mapped()), batch,
                           camera_, out);
  }
  timings_.coverage_ms = timings_.silhouettes_ms = ms_since(start);
  return out;
}

RenderedBin render_bin(const Mesh& part, const std::vector<Eigen::Isometry3d>& part_to_camera,
                       const RenderCamera& camera, const RenderOptions& options) {
  return BinRenderer(part, camera).render(part_to_camera, options);
}

}  // namespace binpick
