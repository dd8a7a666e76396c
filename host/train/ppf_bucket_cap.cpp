#include "host/train/ppf_bucket_cap.hpp"

#include <algorithm>
#include <cmath>

namespace binpick {

std::size_t bucket_cap_entries(double ratio, std::size_t model_points) {
  if (!(ratio > 0)) return 0;
  return std::max<std::size_t>(1, std::size_t(std::llround(ratio * double(model_points))));
}

PpfTable cap_ppf_buckets(const PpfTable& table, std::size_t cap) {
  if (cap == 0 || table.offsets.empty()) return table;
  PpfTable out;
  out.offsets.resize(table.offsets.size());
  out.entries.reserve(table.entries.size());
  for (std::size_t k = 0; k + 1 < table.offsets.size(); ++k) {
    out.offsets[k] = static_cast<std::uint32_t>(out.entries.size());
    const std::size_t first = table.offsets[k], size = table.offsets[k + 1] - first;
    const std::size_t keep = std::min(size, cap);
    for (std::size_t j = 0; j < keep; ++j)
      out.entries.push_back(table.entries[first + j * size / keep]);
  }
  out.offsets.back() = static_cast<std::uint32_t>(out.entries.size());
  return out;
}

}  // namespace binpick
