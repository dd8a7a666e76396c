#include "synth/sensor/sensor_apply.hpp"

#include <utility>

#include "synth/sensor/sensor_params.hpp"
#include "synth/sensor/sensor_stage.hpp"

namespace binpick {
namespace {

DropoutCounts surface_only(const RenderedBin& bin) {
  DropoutCounts c;
  for (float z : bin.depth_mm) ++c.pixels[std::size_t(z > 0 ? Dropout::valid : Dropout::no_surface)];
  return c;
}

SensorImages images_of(const RenderedBin& bin) {
  return {bin.width, bin.height, bin.depth_mm, bin.normals, bin.gray};
}

DropoutCounts store(SensorOutput&& out, RenderedBin& bin) {
  const DropoutCounts counts = count_dropout(out.dropout);
  bin.depth_mm = std::move(out.depth_mm);
  bin.points = std::move(out.points);
  bin.normals = std::move(out.normals);
  bin.gray = std::move(out.gray);
  return counts;
}

}  // namespace

DropoutCounts apply_sensor_model(vkrt::Context& ctx, const RenderCamera& camera,
                                 const SensorModel& model, std::uint64_t seed, RenderedBin& bin) {
  const SensorParams p = sensor_params(camera, model, seed);
  if (model.kind == SensorModel::Kind::ideal) return surface_only(bin);
  return store(SensorStage(ctx, p.width, p.height).run(images_of(bin), p), bin);
}

DropoutCounts apply_sensor_model(SensorStage& stage, const RenderCamera& camera,
                                 const SensorModel& model, std::uint64_t seed, RenderedBin& bin) {
  const SensorParams p = sensor_params(camera, model, seed);
  if (model.kind == SensorModel::Kind::ideal) return surface_only(bin);
  return store(stage.run(images_of(bin), p), bin);
}

DropoutCounts apply_sensor_model_reference(const RenderCamera& camera, const SensorModel& model,
                                           std::uint64_t seed, RenderedBin& bin) {
  const SensorParams p = sensor_params(camera, model, seed);
  if (model.kind == SensorModel::Kind::ideal) return surface_only(bin);
  return store(sensor_model_reference(images_of(bin), p), bin);
}

std::vector<std::uint32_t> valid_pixels_per_part(const RenderedBin& bin) {
  std::vector<std::uint32_t> out(bin.px_visible.size(), 0);
  for (std::size_t i = 0; i < bin.instance.size() && i < bin.depth_mm.size(); ++i) {
    const std::int32_t part = bin.instance[i];
    if (part >= 0 && std::size_t(part) < out.size() && bin.depth_mm[i] > 0) ++out[std::size_t(part)];
  }
  return out;
}

}  // namespace binpick
