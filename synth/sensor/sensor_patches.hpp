// Patchy depth dropout: a structured-light sensor on shiny sheet metal loses depth in patches
// tens of pixels across, not pixel by pixel. The patches are where a smooth random field,
// fixed to the scene (evaluated at the pixel's point in the camera frame, in units of the patch
// size), lies below a threshold. The field is 3D value noise: uniform random values on an
// integer lattice (a hash of the cell and the seed), interpolated trilinearly with smoothstep
// weights, two octaves. docs/sensor_model.md gives the formula and its accuracy.
//
// shaders/sensor_measure.comp repeats these lines operation for operation (marked `precise`),
// as it does sensor_params.hpp's: the device and the C++ reference drop the same pixels (the
// test allows a difference only where the field lies within 1e-5 of the threshold).
#pragma once

#include <cmath>
#include <cstdint>

#include "synth/render/bin_noise.hpp"

namespace binpick {

// The lattice is turned against the camera frame, so that no plane the camera sees face on
// (the bin floor) lies along lattice planes: on such a plane the field would spread wider than
// over space, and the threshold would miss the share. A rotation by 1 rad about
// (0.36, 0.48, 0.8), its entries rounded to multiples of 2^-16 (exact as float and as the GLSL
// literals, orthonormal to 2e-5). Row major.
inline constexpr float kPatchRotation[9] = {
    0.599884033203125f,  -0.5937347412109375f, 0.5363006591796875f,
    0.7526092529296875f, 0.646209716796875f,   -0.12640380859375f,
    -0.271514892578125f, 0.4794464111328125f,  0.834503173828125f};

// The field's hash key: its own stream of the sensor's seed (not the depth noise's).
constexpr std::uint32_t patch_key(std::uint32_t seed_lo, std::uint32_t seed_hi) {
  return pcg_hash(seed_lo ^ pcg_hash(seed_hi ^ 0x243f6a88u));
}

// The uniform value in [0, 1) at lattice point (x, y, z).
constexpr float patch_lattice(std::uint32_t key, std::int32_t x, std::int32_t y, std::int32_t z) {
  std::uint32_t h = pcg_hash(std::uint32_t(x) ^ key);
  h = pcg_hash(h ^ std::uint32_t(y));
  h = pcg_hash(h ^ std::uint32_t(z));
  return float(h >> 8) * 5.9604645e-08f;  // 24 bits, exact in float
}

// Smoothstep, f in [0, 1): the field's gradient is continuous across cell faces (plain
// trilinear weights would leave the lattice's cubes visible in the patches' outlines).
inline float patch_weight(float f) {
  const float a = 3.0f - 2.0f * f;
  return (f * f) * a;
}

inline float patch_lerp(float a, float b, float w) { return a + w * (b - a); }

// One octave of value noise at lattice coordinates (x, y, z), in [0, 1).
inline float patch_value_noise(std::uint32_t key, float x, float y, float z) {
  const float x0 = std::floor(x), y0 = std::floor(y), z0 = std::floor(z);
  const std::int32_t ix = std::int32_t(x0), iy = std::int32_t(y0), iz = std::int32_t(z0);
  const float wx = patch_weight(x - x0), wy = patch_weight(y - y0), wz = patch_weight(z - z0);
  float c[2][2];
  for (std::int32_t k = 0; k < 2; ++k)
    for (std::int32_t j = 0; j < 2; ++j)
      c[k][j] = patch_lerp(patch_lattice(key, ix, iy + j, iz + k),
                           patch_lattice(key, ix + 1, iy + j, iz + k), wx);
  return patch_lerp(patch_lerp(c[0][0], c[0][1], wy), patch_lerp(c[1][0], c[1][1], wy), wz);
}

// The field at lattice coordinates (before the rotation): an octave at the patch size plus half
// an octave at half of it (ragged outlines, as real patches have), in [0, 1.5). Its second
// octave has its own key and is shifted half a cell.
inline float patch_field_lattice(std::uint32_t key, float qx, float qy, float qz) {
  const float* r = kPatchRotation;
  const float x = (r[0] * qx + r[1] * qy) + r[2] * qz;
  const float y = (r[3] * qx + r[4] * qy) + r[5] * qz;
  const float z = (r[6] * qx + r[7] * qy) + r[8] * qz;
  const float coarse = patch_value_noise(key, x, y, z);
  const float fine = patch_value_noise(pcg_hash(key ^ 0x85a308d3u), 2.0f * x + 0.5f,
                                       2.0f * y + 0.5f, 2.0f * z + 0.5f);
  return coarse + 0.5f * fine;
}

// The field at a point of the camera frame (mm); inv_patch_mm = 1 / the patch size.
inline float patch_field(std::uint32_t key, float inv_patch_mm, float x, float y, float z) {
  return patch_field_lattice(key, x * inv_patch_mm, y * inv_patch_mm, z * inv_patch_mm);
}

// The threshold below which the field lies at the share `share` of points in space: from a
// table of the field's quantiles over 2^19 points spread through 2048^3 cells (computed once,
// on first use). Its own sampling error in the share is about 7e-4 (one standard deviation).
// share in [0, 1].
float patch_threshold(double share);

}  // namespace binpick
