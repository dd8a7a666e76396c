// The push constant block of shaders/sensor_projector.comp and shaders/sensor_measure.comp,
// and the few formulas both shaders and the C++ reference evaluate. The GLSL repeats these
// lines operation for operation (marked `precise`, so the device neither fuses nor reorders
// them): the device and the reference then agree bit for bit on which pixels are shadowed.
#pragma once

#include <cmath>
#include <cstdint>

#include "synth/render/bin_camera.hpp"
#include "synth/sensor/sensor_model.hpp"

namespace binpick {

struct SensorParams {
  std::uint32_t width = 0, height = 0;            // camera image
  std::uint32_t proj_width = 0, proj_height = 0;  // projector raster
  float fx = 0, fy = 0, cx = 0, cy = 0;
  // Projector raster coordinates of a pixel (u, v) at depth z (see projector_u/v below).
  float proj_scale = 0, proj_offset_x = 0, proj_fx_baseline = 0, baseline_mm = 0;
  float shadow_tolerance_mm = 0, slope_factor = 0, min_range_mm = 0, max_range_mm = 0;
  float cos_grazing = 0, edge_jump_mm = 0;
  std::int32_t edge_radius = 0;
  float noise_a_mm = 0, noise_b_per_mm = 0, added_sigma_mm = 0;
  float quant_mm = 0, quant_ref_mm = 0;
  std::uint32_t seed_lo = 0, seed_hi = 0;
  std::uint32_t flags = 0;  // kSensorEffects | kSensorShadows | kSensorPatches
  std::uint32_t stage = 0;  // sensor_projector.comp: 0 clears the raster, 1 splats
  float cos_specular = 2;   // > 1: no specular dropout
  // Patchy dropout (sensor_patches.hpp): 1 / the patch size, and the field's threshold.
  float patch_inv_mm = 0, patch_threshold = -1;
};
// 124 of the 128 bytes of push constants every Vulkan device offers.
static_assert(sizeof(SensorParams) == 124, "push constant block of the sensor shaders");

inline constexpr std::uint32_t kSensorEffects = 1u;  // structured light (else: ideal, identity)
inline constexpr std::uint32_t kSensorShadows = 2u;  // baseline != 0
inline constexpr std::uint32_t kSensorPatches = 4u;  // dropout_share > 0
inline constexpr std::uint32_t kShadowGray = 51u;    // the renderer's ambient term, 0.2 * 255
inline constexpr int kMaxFootprint = 8;  // projector cells a side a pixel's splat may cover

// Parameters of one camera and model. The noise stream is the seed mixed with a constant, so
// that the sensor's noise is independent of the renderer's even under the same seed.
// Throws InputError for a bad model, camera, or a projector raster over 64 M cells.
SensorParams sensor_params(const RenderCamera& camera, const SensorModel& model, std::uint64_t seed);

inline bool sensor_in_range(const SensorParams& p, float z) {
  return z >= p.min_range_mm && z <= p.max_range_mm;  // false for NaN
}

// The projector looks along +z from (baseline, 0, 0) with focal length proj_scale * fx, so
// a pixel's point lands proj_fx_baseline / z to the left of where it is in the (scaled) camera
// image; proj_offset_x moves the whole scanning range into the raster.
inline float projector_u(const SensorParams& p, std::uint32_t u, float z) {
  const float a = p.proj_scale * (float(u) + 0.5f);
  const float b = p.proj_fx_baseline / z;
  return (a + p.proj_offset_x) - b;
}
inline float projector_v(const SensorParams& p, std::uint32_t v) {
  return p.proj_scale * (float(v) + 0.5f);
}

}  // namespace binpick
