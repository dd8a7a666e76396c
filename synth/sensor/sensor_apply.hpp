// The sensor model applied to a rendered bin: its depth, points, normals and gray image become
// what a structured-light sensor delivers. Part indices and visible pixel counts stay as
// rendered (the ground truth of what the camera sees); valid_pixels_per_part counts the
// pixels where each part is seen that kept their depth (scene_gt_info.json's px_count_valid
// counts the part's whole silhouette instead: synth/bop_visibility.hpp).
#pragma once

#include <cstdint>
#include <vector>

#include "synth/render/bin_camera.hpp"
#include "synth/render/bin_renderer.hpp"
#include "synth/sensor/sensor_images.hpp"
#include "synth/sensor/sensor_model.hpp"

namespace binpick {

namespace vkrt {
class Context;
}
class SensorStage;

// Render the bin with RenderOptions::noise_sigma_mm = 0 and pass the wanted extra noise as
// model.added_sigma_mm: shadows and edges are found on the ideal depth. The ideal kind leaves
// the bin untouched. `seed` picks the noise (same seed, same output; the stream differs from
// the renderer's under the same seed). Throws InputError for a bad model or a bin that does
// not match the camera.
DropoutCounts apply_sensor_model(vkrt::Context& ctx, const RenderCamera& camera,
                                 const SensorModel& model, std::uint64_t seed, RenderedBin& bin);
// The same with a stage kept for a series of bins of the camera's size (no pipeline builds).
DropoutCounts apply_sensor_model(SensorStage& stage, const RenderCamera& camera,
                                 const SensorModel& model, std::uint64_t seed, RenderedBin& bin);
// The same with the C++ reference instead of the shaders.
DropoutCounts apply_sensor_model_reference(const RenderCamera& camera, const SensorModel& model,
                                           std::uint64_t seed, RenderedBin& bin);

// Per part (RenderedBin::instance), its pixels with depth.
std::vector<std::uint32_t> valid_pixels_per_part(const RenderedBin& bin);

}  // namespace binpick
