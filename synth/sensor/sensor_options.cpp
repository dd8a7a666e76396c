#include "synth/sensor/sensor_options.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <map>

#include <fmt/format.h>

namespace binpick::cli {
namespace {

// A number in [lo, hi]: CLI11's Range lets NaN through, this does not.
CLI::Validator number_in(double lo, double hi, const std::string& unit) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v)) return "not a number: '" + text + "'";
        if (!(v >= lo && v <= hi)) return fmt::format("{} is not in [{}, {}]{}", text, lo, hi, unit);
        return {};
      },
      fmt::format("in [{}, {}]", lo, hi));
}

}  // namespace

void add_sensor_options(CLI::App* verb, SensorModel& m) {
  const std::map<std::string, SensorModel::Kind> kinds{
      {"ideal", SensorModel::Kind::ideal}, {"structured-light", SensorModel::Kind::structured_light}};
  verb->add_option("--sensor-model", m.kind,
                   "depth sensor: ideal (depth as rendered, plus --noise) or structured-light "
                   "(projector shadows, no depth at grazing angles and edges, noise a + b z^2, "
                   "quantisation; docs/sensor_model.md). The options below apply to "
                   "structured-light only")
      ->transform(CLI::Validator(
          [kinds](std::string& value) -> std::string {
            const auto it = kinds.find(value);
            if (it == kinds.end()) return value + " is not ideal or structured-light";
            value = std::to_string(static_cast<int>(it->second));
            return "";
          },
          ""))
      ->option_text("ideal|structured-light")
      ->default_str(sensor_kind_name(m.kind));
  verb->add_option("--baseline", m.baseline_mm,
                   "projector offset from the camera along the camera's x axis, mm (negative: "
                   "towards -x; 0: no projector shadows)")
      ->check(number_in(-2000, 2000, " mm"))
      ->capture_default_str();
  verb->add_option("--projector-scale", m.projector_scale,
                   "resolution of the projector raster that finds shadows, relative to the "
                   "camera's (coarser than 1 leaves no gaps between splats)")
      ->check(number_in(0.125, 4, ""))
      ->capture_default_str();
  verb->add_option("--shadow-tolerance", m.shadow_tolerance_mm,
                   "a pixel is in shadow when it lies more than this (plus a term for its own "
                   "slope) behind the nearest surface the projector sees there, mm")
      ->check(number_in(0, 1000, " mm"))
      ->capture_default_str();
  verb->add_option("--grazing-limit", m.grazing_limit_deg,
                   "no depth where the surface normal is more than this from the ray to the camera "
                   "or to the projector, degrees in (0, 90]; 90: off")
      ->check(number_in(1e-6, 90, " degrees"))
      ->capture_default_str();
  verb->add_option("--specular-cone", m.specular_cone_deg,
                   "shiny parts: no depth where the normal is within this angle of the bisector "
                   "of the rays to camera and projector (the projector's mirror reflection "
                   "saturates the camera), degrees in [0, 45]; 0: off")
      ->check(number_in(0, 45, " degrees"))
      ->capture_default_str();
  verb->add_option("--edge-jump", m.edge_jump_mm,
                   "a depth step between neighbouring pixels larger than this is a discontinuity, "
                   "mm (also: neighbours closer than this are one surface for the shadows)")
      ->check(number_in(1e-6, 10000, " mm"))
      ->capture_default_str();
  verb->add_option("--edge-radius", m.edge_radius_px,
                   "pixels within this many pixels of a discontinuity or of a pixel without "
                   "surface have no depth, in [0, 5]; 0: off")
      ->check(CLI::Range(0, 5))
      ->capture_default_str();
  verb->add_option("--noise-a", m.noise_a_mm,
                   "axial noise sigma(z) = a + b z^2: the constant a, mm")
      ->check(number_in(0, 100, " mm"))
      ->capture_default_str();
  verb->add_option("--noise-b", m.noise_b_per_mm,
                   "axial noise sigma(z) = a + b z^2: the factor b, 1/mm (z in mm)")
      ->check(number_in(0, 1e-3, " 1/mm"))
      ->capture_default_str();
  verb->add_option("--quantisation", m.quantisation_mm,
                   "depth step at --quantisation-ref, mm (0: none)")
      ->check(number_in(0, 100, " mm"))
      ->capture_default_str();
  verb->add_option("--quantisation-ref", m.quantisation_ref_mm,
                   "depth where the step is --quantisation; it grows with (z / ref)^2 as a "
                   "triangulation sensor's does, mm (0: the same step at every depth)")
      ->check(number_in(0, 100000, " mm"))
      ->capture_default_str();
  verb->add_option_function<std::vector<double>>(
          "--range",
          [&m](const std::vector<double>& r) {
            m.min_range_mm = r.at(0);
            m.max_range_mm = r.at(1);
          },
          "scanning range MIN,MAX in mm: no depth nearer or farther")
      ->delimiter(',')
      ->expected(2)
      ->check(number_in(1e-6, 1e6, " mm"))
      ->default_str(fmt::format("{},{}", m.min_range_mm, m.max_range_mm));
  verb->add_option("--dropout-share", m.dropout_share,
                   "shiny metal: share of the pixels that would have depth that lose it in "
                   "patches fixed to the surfaces, in [0, 0.95]; 0: off")
      ->check(number_in(0, 0.95, ""))
      ->capture_default_str();
  verb->add_option("--dropout-patch", m.dropout_patch_mm,
                   "size of those patches on the surface (the random field's correlation "
                   "length), mm in [1, 1000]")
      ->check(number_in(1, 1000, " mm"))
      ->capture_default_str();
}

}  // namespace binpick::cli

namespace binpick {

nlohmann::json sensor_model_json(const SensorModel& m) {
  nlohmann::json out = {{"kind", sensor_kind_name(m.kind)},
                        {"baseline_mm", m.baseline_mm},
                        {"projector_scale", m.projector_scale},
                        {"shadow_tolerance_mm", m.shadow_tolerance_mm},
                        {"grazing_limit_deg", m.grazing_limit_deg},
                        {"specular_cone_deg", m.specular_cone_deg},
                        {"edge_jump_mm", m.edge_jump_mm},
                        {"edge_radius_px", m.edge_radius_px},
                        {"noise_a_mm", m.noise_a_mm},
                        {"noise_b_per_mm", m.noise_b_per_mm},
                        {"added_sigma_mm", m.added_sigma_mm},
                        {"quantisation_mm", m.quantisation_mm},
                        {"quantisation_ref_mm", m.quantisation_ref_mm},
                        {"min_range_mm", m.min_range_mm},
                        {"max_range_mm", m.max_range_mm}};
  // Only when on: a dataset made before the patches existed, or without them, keeps the same
  // manifest and stays resumable; any share or patch size asked for is compared.
  if (m.dropout_share > 0) {
    out["dropout_share"] = m.dropout_share;
    out["dropout_patch_mm"] = m.dropout_patch_mm;
  }
  return out;
}

}  // namespace binpick
