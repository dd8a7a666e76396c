#include "synth/sensor/sensor_patches.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace binpick {
namespace {

constexpr std::size_t kSamples = std::size_t(1) << 19;  // a quarter of a second, once
constexpr std::size_t kQuantiles = 4096;  // table steps: a share step of 1/4096

// The field's quantiles k / kQuantiles, k = 0 .. kQuantiles. Value noise is not uniform (the
// interpolation averages lattice values, so it gathers around the middle), hence a table and
// not the share itself. The lattice's values are independent uniform numbers whatever the
// seed, so one table, from a fixed key, serves every seed. The points are spread over 2048^3
// cells: nearly every sample sees its own cells, and the sample is as good as independent.
std::array<float, kQuantiles + 1> quantile_table() {
  std::vector<float> field(kSamples);
  const std::uint32_t key = patch_key(0x51ed270bu, 0x3c6ef372u);
  auto coordinate = [](std::uint32_t h) { return (float(h >> 8) * 5.9604645e-08f - 0.5f) * 2048.0f; };
  for (std::size_t k = 0; k < kSamples; ++k) {
    const std::uint32_t hx = pcg_hash(std::uint32_t(k) ^ 0x9e3779b9u), hy = pcg_hash(hx), hz = pcg_hash(hy);
    field[k] = patch_field_lattice(key, coordinate(hx), coordinate(hy), coordinate(hz));
  }
  std::sort(field.begin(), field.end());
  std::array<float, kQuantiles + 1> table{};
  for (std::size_t k = 0; k <= kQuantiles; ++k)
    table[k] = field[std::min(kSamples - 1, k * (kSamples / kQuantiles))];
  return table;
}

}  // namespace

float patch_threshold(double share) {
  static const std::array<float, kQuantiles + 1> table = quantile_table();
  if (!(share > 0)) return -1.0f;  // below every value: nothing drops
  if (share >= 1) return 2.0f;     // above every value (the field is below 1.5)
  const double at = share * kQuantiles;
  const std::size_t k = std::min(kQuantiles - 1, std::size_t(at));
  const double t = at - double(k);
  return float(table[k] + t * (table[k + 1] - table[k]));
}

}  // namespace binpick
