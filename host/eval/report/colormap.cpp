#include "host/eval/report/colormap.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace binpick::eval {
namespace {

// viridis (matplotlib's, CC0) at 0, 0.1, ..., 1; linear in between stays within a few levels
// of the full 256-entry table.
constexpr std::array<Rgb, 11> kViridis{{{0x44, 0x01, 0x54}, {0x48, 0x24, 0x75}, {0x41, 0x44, 0x87},
                                        {0x35, 0x5f, 0x8d}, {0x2a, 0x78, 0x8e}, {0x21, 0x91, 0x8c},
                                        {0x22, 0xa8, 0x84}, {0x44, 0xbf, 0x70}, {0x7a, 0xd1, 0x51},
                                        {0xbd, 0xdf, 0x26}, {0xfd, 0xe7, 0x25}}};

}  // namespace

Rgb viridis(double t) {
  if (!(t >= 0)) t = 0;  // NaN too
  t = std::min(t, 1.0);
  const double x = t * double(kViridis.size() - 1);
  const std::size_t i = std::min<std::size_t>(std::size_t(x), kViridis.size() - 2);
  const double f = x - double(i);
  Rgb c;
  for (int k = 0; k < 3; ++k)
    c[k] = std::uint8_t(std::lround(kViridis[i][k] * (1 - f) + kViridis[i + 1][k] * f));
  return c;
}

std::string hex(const Rgb& c) { return fmt::format("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]); }

Rgb rank_colour(int rank) {
  // Tableau-like, bright enough on a dark grey picture.
  static constexpr std::array<Rgb, 8> kColours{{{255, 127, 14}, {31, 180, 255}, {44, 220, 44},
                                                {240, 60, 60},  {190, 120, 255}, {255, 230, 0},
                                                {0, 220, 200},  {255, 120, 200}}};
  return kColours[std::size_t(((rank % 8) + 8) % 8)];
}

}  // namespace binpick::eval
