// The images the sensor model reads and writes, and why a pixel has no depth.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace binpick {

// Why a pixel has no depth (first reason that applies, in this order); valid: it has depth.
enum class Dropout : std::uint8_t {
  valid = 0, no_surface, out_of_range, shadow, grazing, specular, edge, patch
};
inline constexpr std::size_t kDropoutKinds = 8;
std::string dropout_name(Dropout d);

// The ideal images as the renderer delivers them (RenderedBin's fields of the same names).
struct SensorImages {
  std::uint32_t width = 0, height = 0;
  std::vector<float> depth_mm;     // z along the optical axis; <= 0 or not finite: no surface
  std::vector<float> normals;      // 3 a pixel, camera frame (any length; 0: facing the camera)
  std::vector<std::uint8_t> gray;  // intensity
};

// What the sensor delivers: depth 0, points 0 and normals 0 where it has no depth; gray as
// rendered except in projector shadows, which are dark (kShadowGray, the renderer's ambient
// level: the camera still sees the surface, lit by ambient light only).
struct SensorOutput {
  std::vector<float> depth_mm;
  std::vector<float> points;        // 3 a pixel, camera frame, mm: the ray times the depth
  std::vector<float> normals;       // 3 a pixel, the input normal where there is depth
  std::vector<std::uint8_t> gray;
  std::vector<std::uint8_t> dropout;  // a Dropout a pixel
};

// Pixels per Dropout reason.
struct DropoutCounts {
  std::array<std::size_t, kDropoutKinds> pixels{};
  std::size_t operator[](Dropout d) const { return pixels[std::size_t(d)]; }
  std::size_t surface() const;  // pixels that show a surface (all but no_surface)
  std::string summary() const;  // "valid 61.2 % of surface pixels (shadow 20.1 %, ...)"
};
DropoutCounts count_dropout(const std::vector<std::uint8_t>& dropout);

}  // namespace binpick
