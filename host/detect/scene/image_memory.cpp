#include "host/detect/scene/image_memory.hpp"

#include <unistd.h>

#include <fmt/format.h>

#include "host/core/error.hpp"

namespace binpick {

std::uint64_t detect_memory_estimate(std::uint64_t width, std::uint64_t height) {
  constexpr std::uint64_t kFixed = 160ull << 20, kPerPixel = 64;
  return kFixed + width * height * kPerPixel;
}

std::uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? std::uint64_t(pages) * std::uint64_t(page) : 0;
}

void check_image_fits_in_memory(std::uint64_t width, std::uint64_t height,
                                std::uint64_t available) {
  if (available == 0) return;
  const std::uint64_t need = detect_memory_estimate(width, height);
  if (need <= available) return;
  constexpr double kGiB = double(1ull << 30);
  throw InputError(fmt::format(
      "the depth image is {} x {} pixels ({:.0f} megapixels): detection needs about {:.1f} GiB "
      "for it, more than this machine's {:.1f} GiB; crop or downsample the image",
      width, height, double(width) * double(height) / 1e6, double(need) / kGiB,
      double(available) / kGiB));
}

}  // namespace binpick
