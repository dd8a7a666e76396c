// What a structured-light depth sensor makes of an ideal rendered depth image: projector
// shadows (the projector sits a baseline away from the camera), no depth at grazing angles and
// at depth discontinuities, axial noise growing with the square of the distance, depth
// quantisation, a scanning range and, optionally, specular highlights and depth lost in patches. docs/sensor_model.md
// gives the formulas and where the default figures come from.
#pragma once

#include <cstdint>
#include <string>

namespace binpick {

struct SensorModel {
  enum class Kind { ideal, structured_light };
  Kind kind = Kind::ideal;  // ideal: the rendered depth as it is

  // The projector's optical centre is at (baseline_mm, 0, 0) in the camera frame (x right),
  // looking the same way as the camera. 0: no projector shadows. Default: Photoneo PhoXi M.
  double baseline_mm = 350;
  // The projector raster used to find shadows, relative to the camera's resolution: coarser
  // than the camera (< 1) so that a near surface leaves no holes a far one shows through.
  double projector_scale = 0.5;
  // A pixel is lit when its depth is within this (plus its own depth change from pixel to
  // pixel, scaled by the raster's coarseness) of the nearest surface the projector sees there.
  double shadow_tolerance_mm = 2;
  // No depth where the angle between the surface normal and the ray to the camera, or to the
  // projector, exceeds this. 90: off.
  double grazing_limit_deg = 75;
  // Shiny metal: no depth where the normal is within this angle of the bisector of the rays to
  // the camera and the projector, i.e. where the mirror reflection of the projector's light
  // enters the camera (within twice the angle) and saturates it. 0: off (matte surfaces).
  double specular_cone_deg = 0;
  // No depth within edge_radius_px pixels (square neighbourhood) of a depth discontinuity or
  // of a pixel without surface (decoding fails across the edge). Radius 0: off. A neighbour is
  // across a discontinuity when its depth is more than edge_jump_mm off the pixel's tangent
  // plane (from its normal): a steep surface is continuous, a step is not. The same test tells
  // the projector splat which neighbours belong to the same surface.
  double edge_jump_mm = 5;
  int edge_radius_px = 1;
  // Axial noise sigma(z) = noise_a_mm + noise_b_per_mm z^2 (z in mm), Gaussian along the ray,
  // combined in quadrature with added_sigma_mm (binpick synth's --noise, a fraction of the
  // diameter, when the lead wires it this way).
  double noise_a_mm = 0.05;
  double noise_b_per_mm = 1.2e-7;
  double added_sigma_mm = 0;
  // Depth quantisation: a step of quantisation_mm at depth quantisation_ref_mm, growing with
  // (z / ref)^2 as a triangulation sensor's disparity steps do; ref 0: the same step at every
  // depth; step 0: none.
  double quantisation_mm = 0.05;
  double quantisation_ref_mm = 1000;
  // Scanning range: no depth nearer or farther (and the nearer surfaces cast no shadow).
  double min_range_mm = 300, max_range_mm = 3000;
  // Shiny sheet metal: depth lost in patches fixed to the surfaces, about dropout_patch_mm
  // across (a smooth random field below a threshold: synth/sensor/sensor_patches.hpp), taking
  // this share, in [0, 0.95], of the pixels that would otherwise have depth. 0: off (the output
  // is the same as without the field, bit for bit). The patch size is in [1, 1000] mm.
  double dropout_share = 0;
  double dropout_patch_mm = 20;
};

// Throws InputError naming the command-line option of the first field that is NaN or out of
// range (docs/cli.md lists the ranges).
void check(const SensorModel& model);

// "ideal" / "structured-light", as on the command line.
std::string sensor_kind_name(SensorModel::Kind kind);
SensorModel::Kind parse_sensor_kind(const std::string& name);  // InputError if unknown

}  // namespace binpick
