#include "host/formats/bop/png_image.hpp"

#include <png.h>

#include <cstring>
#include <ostream>
#include <string>

#include "host/core/error.hpp"
#include "host/core/atomic_file.hpp"
#include "host/core/read_file.hpp"

namespace binpick {
namespace {

// libpng reports errors through a callback that must not return: throw out of it (libpng is
// built as C, but Debian's is compiled with unwind tables, and this is what its C++ users do).
[[noreturn]] void on_png_error(png_structp, png_const_charp message) {
  throw std::runtime_error(message ? message : "libpng error");
}
void on_png_warning(png_structp, png_const_charp) {}

// Writes rows of height x (width * channels) samples of type T (8 or 16 bits).
template <class T>
void write_samples(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
                   int channels, const std::vector<T>& samples) {
  if (samples.size() != std::size_t(width) * height * std::size_t(channels) || width == 0 ||
      height == 0)
    throw InputError("cannot write " + path.string() + ": image size does not match its pixels");
  const int color_type = channels == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY;
  write_file_atomically(path, [&](std::ostream& out) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, on_png_error, on_png_warning);
    png_infop info = png_create_info_struct(png);
    try {
      png_set_write_fn(png, &out,
                       [](png_structp p, png_bytep data, png_size_t n) {
                         static_cast<std::ostream*>(png_get_io_ptr(p))
                             ->write(reinterpret_cast<const char*>(data), std::streamsize(n));
                       },
                       [](png_structp p) { static_cast<std::ostream*>(png_get_io_ptr(p))->flush(); });
      png_set_IHDR(png, info, width, height, 8 * sizeof(T), color_type,
                   PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
      png_set_compression_level(png, 3);  // depth maps compress well already; favour speed
      png_write_info(png, info);
      if (sizeof(T) == 2) png_set_swap(png);  // PNG is big-endian, this host is not
      const std::size_t row = std::size_t(width) * std::size_t(channels);
      for (std::uint32_t y = 0; y < height; ++y)
        png_write_row(png, reinterpret_cast<png_const_bytep>(&samples[std::size_t(y) * row]));
      png_write_end(png, nullptr);
    } catch (const std::runtime_error& e) {
      png_destroy_write_struct(&png, &info);
      throw InputError("cannot write " + path.string() + ": " + e.what());
    }
    png_destroy_write_struct(&png, &info);
  });
}

template <class T>
void write_gray(const std::filesystem::path& path, const GrayImage<T>& image) {
  write_samples(path, image.width, image.height, 1, image.pixels);
}

struct MemoryReader {
  std::string_view bytes;
  std::size_t offset = 0;
};

template <class T>
GrayImage<T> decode_gray(std::string_view bytes, const std::string& name) {
  if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8))
    throw InputError(name + " is not a PNG file");
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, on_png_error, on_png_warning);
  png_infop info = png_create_info_struct(png);
  MemoryReader reader{bytes};
  GrayImage<T> image;
  try {
    png_set_read_fn(png, &reader, [](png_structp p, png_bytep data, png_size_t n) {
      auto* r = static_cast<MemoryReader*>(png_get_io_ptr(p));
      if (r->offset + n > r->bytes.size()) throw std::runtime_error("the file is truncated");
      std::memcpy(data, r->bytes.data() + r->offset, n);
      r->offset += n;
    });
    png_read_info(png, info);
    const int depth = png_get_bit_depth(png, info);
    int type = png_get_color_type(png, info);
    // An 8-bit intensity image may come as colour (BOP's rgb/): read its luma.
    if (sizeof(T) == 1 && depth == 8 && (type & PNG_COLOR_MASK_COLOR) &&
        type != PNG_COLOR_TYPE_PALETTE) {
      png_set_rgb_to_gray_fixed(png, 1, -1, -1);
      type &= ~PNG_COLOR_MASK_COLOR;
    }
    if (sizeof(T) == 1 && depth == 8 && (type & PNG_COLOR_MASK_ALPHA)) {
      png_set_strip_alpha(png);
      type &= ~PNG_COLOR_MASK_ALPHA;
    }
    png_read_update_info(png, info);
    if (type != PNG_COLOR_TYPE_GRAY || depth != int(8 * sizeof(T)))
      throw std::runtime_error("expected a " + std::to_string(8 * sizeof(T)) +
                               "-bit single-channel image, found bit depth " + std::to_string(depth) +
                               " and colour type " + std::to_string(type));
    if (sizeof(T) == 2) png_set_swap(png);
    image.width = png_get_image_width(png, info);
    image.height = png_get_image_height(png, info);
    // Grown row by row: a header that announces more rows than the file holds must fail on the
    // missing data, not on allocating them all first (a 60-byte file can claim 10^12 pixels).
    for (std::uint32_t y = 0; y < image.height; ++y) {
      image.pixels.resize(std::size_t(y + 1) * image.width);
      png_read_row(png, reinterpret_cast<png_bytep>(&image.pixels[std::size_t(y) * image.width]), nullptr);
    }
    png_read_end(png, nullptr);
  } catch (const std::runtime_error& e) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw InputError("cannot read " + name + ": " + e.what());
  }
  png_destroy_read_struct(&png, &info, nullptr);
  return image;
}

}  // namespace

void write_png(const std::filesystem::path& path, const GrayImage<std::uint16_t>& image) {
  write_gray(path, image);
}
void write_png(const std::filesystem::path& path, const GrayImage<std::uint8_t>& image) {
  write_gray(path, image);
}
void write_png(const std::filesystem::path& path, const RgbImage& image) {
  write_samples(path, image.width, image.height, 3, image.pixels);
}
GrayImage<std::uint16_t> read_png16(const std::filesystem::path& path) {
  return decode_gray<std::uint16_t>(read_file_bytes(path), path.string());
}
GrayImage<std::uint8_t> read_png8(const std::filesystem::path& path) {
  return decode_gray<std::uint8_t>(read_file_bytes(path), path.string());
}
GrayImage<std::uint16_t> decode_png16(std::string_view bytes, const std::string& name) {
  return decode_gray<std::uint16_t>(bytes, name);
}
GrayImage<std::uint8_t> decode_png8(std::string_view bytes, const std::string& name) {
  return decode_gray<std::uint8_t>(bytes, name);
}

}  // namespace binpick
