// Grey PNG images as BOP stores them: 16-bit depth, 8-bit intensity and masks.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace binpick {

template <class T>
struct GrayImage {
  std::uint32_t width = 0, height = 0;
  std::vector<T> pixels;  // row-major
};

// 8-bit RGB, for pictures (false-colour depth, overlays); not a BOP file.
struct RgbImage {
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // r, g, b per pixel, row-major
};

// Written atomically (no partial file on error).
void write_png(const std::filesystem::path& path, const GrayImage<std::uint16_t>& image);
void write_png(const std::filesystem::path& path, const GrayImage<std::uint8_t>& image);
void write_png(const std::filesystem::path& path, const RgbImage& image);

// Reads a single-channel PNG of the given depth (read_png8 also takes an 8-bit RGB or RGBA image
// and returns its luma, as BOP's rgb/ images come); a missing, corrupt or truncated file, or one
// of another bit depth or colour type, is an InputError naming the file.
GrayImage<std::uint16_t> read_png16(const std::filesystem::path& path);
GrayImage<std::uint8_t> read_png8(const std::filesystem::path& path);

// The same for a PNG file held in memory; name is what errors call it.
GrayImage<std::uint16_t> decode_png16(std::string_view bytes, const std::string& name);
GrayImage<std::uint8_t> decode_png8(std::string_view bytes, const std::string& name);

}  // namespace binpick
