#include "synth/sensor/sensor_images.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace binpick {

std::string dropout_name(Dropout d) {
  switch (d) {
    case Dropout::valid: return "valid";
    case Dropout::no_surface: return "no surface";
    case Dropout::out_of_range: return "out of range";
    case Dropout::shadow: return "shadow";
    case Dropout::grazing: return "grazing";
    case Dropout::specular: return "specular";
    case Dropout::edge: return "edge";
    case Dropout::patch: return "patch";
  }
  return "unknown";
}

std::size_t DropoutCounts::surface() const {
  std::size_t n = 0;
  for (std::size_t k = 0; k < kDropoutKinds; ++k)
    if (Dropout(k) != Dropout::no_surface) n += pixels[k];
  return n;
}

std::string DropoutCounts::summary() const {
  const double total = double(std::max<std::size_t>(surface(), 1));
  std::string out = fmt::format("valid {:.1f} % of surface pixels (", 100 * (*this)[Dropout::valid] / total);
  const char* sep = "";
  for (Dropout d : {Dropout::shadow, Dropout::grazing, Dropout::specular, Dropout::edge,
                    Dropout::patch, Dropout::out_of_range}) {
    out += fmt::format("{}{} {:.1f} %", sep, dropout_name(d), 100 * (*this)[d] / total);
    sep = ", ";
  }
  return out + ")";
}

DropoutCounts count_dropout(const std::vector<std::uint8_t>& dropout) {
  DropoutCounts c;
  for (std::uint8_t d : dropout)
    if (d < kDropoutKinds) ++c.pixels[d];
  return c;
}

}  // namespace binpick
