#include "synth/sensor/sensor_model.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "synth/sensor/sensor_params.hpp"
#include "synth/sensor/sensor_patches.hpp"

namespace binpick {
namespace {

// Throws unless lo <= v <= hi (NaN fails), naming the option.
void within(double v, double lo, double hi, const char* option, const char* unit) {
  if (!(v >= lo && v <= hi))
    throw InputError(fmt::format("{} must be in [{}, {}]{}, got {}", option, lo, hi, unit, v));
}

}  // namespace

void check(const SensorModel& m) {
  within(m.baseline_mm, -2000, 2000, "--baseline", " mm");
  within(m.projector_scale, 0.125, 4, "--projector-scale", "");
  within(m.shadow_tolerance_mm, 0, 1000, "--shadow-tolerance", " mm");
  if (!(m.grazing_limit_deg > 0 && m.grazing_limit_deg <= 90))
    throw InputError(fmt::format("--grazing-limit must be in (0, 90] degrees, got {}", m.grazing_limit_deg));
  within(m.specular_cone_deg, 0, 45, "--specular-cone", " degrees");
  if (!(m.edge_jump_mm > 0 && m.edge_jump_mm <= 10000))
    throw InputError(fmt::format("--edge-jump must be in (0, 10000] mm, got {}", m.edge_jump_mm));
  within(m.edge_radius_px, 0, 5, "--edge-radius", " pixels");
  within(m.noise_a_mm, 0, 100, "--noise-a", " mm");
  within(m.noise_b_per_mm, 0, 1e-3, "--noise-b", " 1/mm");
  within(m.added_sigma_mm, 0, 10000, "--noise (as sigma)", " mm");
  within(m.quantisation_mm, 0, 100, "--quantisation", " mm");
  within(m.quantisation_ref_mm, 0, 100000, "--quantisation-ref", " mm");
  if (!(m.min_range_mm > 0 && m.min_range_mm < m.max_range_mm && m.max_range_mm <= 1e6))
    throw InputError(fmt::format("--range must be MIN,MAX with 0 < MIN < MAX <= 1e6 mm, got {},{}",
                                 m.min_range_mm, m.max_range_mm));
  within(m.dropout_share, 0, 0.95, "--dropout-share", "");
  // At least 1 mm: smaller patches are single pixels at any sensible resolution, and the
  // field's lattice coordinates (point / patch) stay far inside int32 over the whole range.
  within(m.dropout_patch_mm, 1, 1000, "--dropout-patch", " mm");
  // The other structured-light options are harmless with the ideal sensor; a share asked for
  // and silently not applied would be measured as if it were.
  if (m.dropout_share > 0 && m.kind != SensorModel::Kind::structured_light)
    throw InputError("--dropout-share needs --sensor-model structured-light");
}

std::string sensor_kind_name(SensorModel::Kind kind) {
  return kind == SensorModel::Kind::ideal ? "ideal" : "structured-light";
}

SensorModel::Kind parse_sensor_kind(const std::string& name) {
  if (name == "ideal") return SensorModel::Kind::ideal;
  if (name == "structured-light") return SensorModel::Kind::structured_light;
  throw InputError("--sensor-model must be ideal or structured-light, got '" + name + "'");
}

SensorParams sensor_params(const RenderCamera& c, const SensorModel& m, std::uint64_t seed) {
  check(m);
  check_camera(c);
  SensorParams p;
  p.width = c.width, p.height = c.height;
  p.fx = float(c.fx), p.fy = float(c.fy), p.cx = float(c.cx), p.cy = float(c.cy);
  const bool structured = m.kind == SensorModel::Kind::structured_light;
  const bool shadows = structured && m.baseline_mm != 0;
  const bool patches = structured && m.dropout_share > 0;
  p.flags = (structured ? kSensorEffects : 0u) | (shadows ? kSensorShadows : 0u) |
            (patches ? kSensorPatches : 0u);

  // The shift fx_p b / z of the scanning range spans fx_p |b| (1/min - 1/max) cells; the
  // offset puts its smallest value at 0. One spare cell for the floor of the far edge.
  const double s = m.projector_scale, fxb = s * c.fx * m.baseline_mm;
  const double spread = std::fabs(fxb) * (1 / m.min_range_mm - 1 / m.max_range_mm);
  const double pw = shadows ? std::ceil(s * c.width + spread) + 1 : 1;
  const double ph = shadows ? std::ceil(s * c.height) + 1 : 1;
  if (pw * ph > 64.0 * 1024 * 1024)
    throw InputError(fmt::format(
        "the projector raster would be {:.0f} x {:.0f} cells: raise the --range minimum or lower "
        "--baseline or --projector-scale", pw, ph));
  p.proj_width = std::uint32_t(pw), p.proj_height = std::uint32_t(ph);
  p.proj_scale = float(s);
  p.proj_fx_baseline = float(fxb);
  p.proj_offset_x = float(fxb / (m.baseline_mm > 0 ? m.min_range_mm : m.max_range_mm));
  p.baseline_mm = float(m.baseline_mm);
  p.shadow_tolerance_mm = float(m.shadow_tolerance_mm);
  // A projector cell spans 1 / s pixels; a splat reaches one pixel further (to its right and
  // lower neighbours): the nearest depth found in a pixel's cell can come from that far away.
  p.slope_factor = float(1 / s + 2);
  p.min_range_mm = float(m.min_range_mm), p.max_range_mm = float(m.max_range_mm);
  p.cos_grazing = m.grazing_limit_deg >= 90 ? -2.0f  // off: even back faces pass
                                            : float(std::cos(m.grazing_limit_deg * M_PI / 180));
  p.cos_specular = m.specular_cone_deg > 0 ? float(std::cos(m.specular_cone_deg * M_PI / 180)) : 2.0f;
  p.edge_jump_mm = float(m.edge_jump_mm);
  p.edge_radius = m.edge_radius_px;
  p.noise_a_mm = float(m.noise_a_mm), p.noise_b_per_mm = float(m.noise_b_per_mm);
  p.added_sigma_mm = float(m.added_sigma_mm);
  p.quant_mm = float(m.quantisation_mm), p.quant_ref_mm = float(m.quantisation_ref_mm);
  const std::uint64_t stream = seed ^ 0x5e45e0a7b1c2d3f5ull;  // not the renderer's stream
  p.seed_lo = std::uint32_t(stream), p.seed_hi = std::uint32_t(stream >> 32);
  if (patches) {
    p.patch_inv_mm = float(1 / m.dropout_patch_mm);
    p.patch_threshold = patch_threshold(m.dropout_share);
  }
  return p;
}

}  // namespace binpick
