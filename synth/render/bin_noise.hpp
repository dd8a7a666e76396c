// The sensor noise of a synthetic bin: a counter-based random number per pixel, so the compute
// shader (bin_gbuffer.comp, which repeats these lines in GLSL) and its C++ reference draw the
// same numbers without sharing state: the integers are identical, the Gaussian agrees to the
// precision of the device's log and cos.
#pragma once

#include <cmath>
#include <cstdint>

namespace binpick {

// The output permutation of PCG (RXS-M-XS), a bijection of 32-bit words with good avalanche.
constexpr std::uint32_t pcg_hash(std::uint32_t x) {
  const std::uint32_t state = x * 747796405u + 2891336453u;
  const std::uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// The first of the two words drawn for `pixel` (row-major index) under `seed`.
constexpr std::uint32_t pixel_hash(std::uint64_t seed, std::uint32_t pixel) {
  const std::uint32_t key = pcg_hash(std::uint32_t(seed) ^ pcg_hash(std::uint32_t(seed >> 32)));
  return pcg_hash(pixel ^ key);
}

// A standard normal number for `pixel` (Box-Muller on two 24-bit uniforms, in float).
inline float pixel_gaussian(std::uint64_t seed, std::uint32_t pixel) {
  const std::uint32_t h1 = pixel_hash(seed, pixel), h2 = pcg_hash(h1);
  const float u1 = float((h1 >> 8) + 1u) * 5.9604645e-08f;  // (0, 1]: log stays finite
  const float u2 = float(h2 >> 8) * 5.9604645e-08f;         // [0, 1)
  return std::sqrt(-2.0f * std::log(u1)) * std::cos(6.2831853f * u2);
}

}  // namespace binpick
