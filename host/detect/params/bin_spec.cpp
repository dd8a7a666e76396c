#include "host/detect/params/bin_spec.hpp"

#include <charconv>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/detect/params/bin_mesh_interior.hpp"
#include "host/formats/mesh/load_model.hpp"

namespace binpick {
namespace {

// Comma-separated finite numbers; false for anything else (empty items, junk, NaN, inf).
bool parse_numbers(const std::string& text, std::vector<double>& out) {
  out.clear();
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos
                                                                              : comma - start);
    double v = 0;
    const char* b = item.data();
    const char* e = item.data() + item.size();
    while (b < e && *b == ' ') ++b;
    while (e > b && e[-1] == ' ') --e;
    const auto [end, ec] = std::from_chars(b, e, v);
    if (b == e || ec != std::errc() || end != e || !std::isfinite(v)) return false;
    out.push_back(v);
    if (comma == std::string::npos) return true;
    start = comma + 1;
  }
}

}  // namespace

std::optional<RoiSpec> parse_roi(const std::string& text) {
  if (text.empty()) return std::nullopt;
  const auto fail = [&](const std::string& why) {
    return InputError(fmt::format(
        "'{}': {}; expected camera:x0,y0,z0,x1,y1,z1 or bin:x0,y0,z0,x1,y1,z1 (mm)", text, why));
  };
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos) throw fail("no frame");
  RoiSpec roi;
  const std::string frame = text.substr(0, colon);
  if (frame == "camera")
    roi.frame = RoiSpec::Frame::camera;
  else if (frame == "bin")
    roi.frame = RoiSpec::Frame::bin;
  else
    throw fail("unknown frame '" + frame + "'");
  std::vector<double> v;
  if (!parse_numbers(text.substr(colon + 1), v) || v.size() != 6)
    throw fail("not six finite numbers");
  roi.lo = {v[0], v[1], v[2]};
  roi.hi = {v[3], v[4], v[5]};
  for (int a = 0; a < 3; ++a)
    if (!(roi.lo[a] < roi.hi[a]))
      throw fail(fmt::format("the box is empty or inverted along {} ({} >= {})", "xyz"[a],
                             roi.lo[a], roi.hi[a]));
  return roi;
}

BinSpec parse_bin(const std::string& text) {
  BinSpec spec;
  if (text == "none") return spec;
  if (text == "auto") {
    spec.mode = BinSpec::Mode::find;
    return spec;
  }
  if (text.rfind("mesh:", 0) == 0) {  // the size from the bin's model
    try {
      spec.size = bin_interior_from_mesh(load_model(text.substr(5), {}));
    } catch (const InputError& e) {
      throw InputError(fmt::format("'{}': {}", text, e.what()));
    }
    spec.mode = BinSpec::Mode::sized;
    return spec;
  }
  std::vector<double> v;
  if (!parse_numbers(text, v) || v.size() != 3 || !(v[0] > 0 && v[1] > 0 && v[2] > 0))
    throw InputError(fmt::format(
        "'{}': expected none, auto, the interior size W,D,H (three positive numbers, mm) or "
        "mesh:FILE (the bin's model)",
        text));
  spec.mode = BinSpec::Mode::sized;
  spec.size = {v[0], v[1], v[2]};
  return spec;
}

}  // namespace binpick
