#include "synth/physics/bin_capacity.hpp"

#include <cmath>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "synth/physics/mass_properties.hpp"

namespace binpick {

BinCapacity estimate_bin_capacity(const Eigen::Vector3d& bin_size_mm,
                                  const std::vector<const Mesh*>& meshes,
                                  const std::vector<int>& counts) {
  if (meshes.size() != counts.size())
    throw InputError("bin capacity: one count per kind of part is needed");
  BinCapacity c;
  c.bin_volume_mm3 = bin_size_mm.prod();
  double total_volume = 0;
  long long total_count = 0;
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    if (counts[k] <= 0) continue;
    total_volume += mass_properties(*meshes[k]).volume * counts[k];
    total_count += counts[k];
  }
  c.part_volume_mm3 = total_count > 0 ? total_volume / double(total_count) : 0.0;
  const double fit = c.part_volume_mm3 > 0
                         ? c.bin_volume_mm3 * c.packing_fraction / c.part_volume_mm3
                         : 0.0;
  c.parts = int(std::min(std::floor(fit), 2.0e9));
  return c;
}

void check_part_size(const std::string& what, double diameter_mm, const Eigen::Vector3d& bin_size_mm) {
  if (diameter_mm < kMinPartDiameterMm)
    throw InputError(fmt::format(
        "{}: the part's diameter is {:.3g} mm; the physics needs parts of at least {:g} mm (its "
        "collision margin is 0.4 mm): give the model's units with --unit-scale or its size "
        "with --diameter",
        what, diameter_mm, kMinPartDiameterMm));
  const double widest = std::min(bin_size_mm.x(), bin_size_mm.y());
  if (diameter_mm > widest)
    throw InputError(fmt::format(
        "{}: the part's diameter is {:.4g} mm, more than the bin's interior is wide ({:g} x "
        "{:g} mm): give the model's units with --unit-scale or its size with --diameter, or a "
        "larger --bin-size W,D,H",
        what, diameter_mm, bin_size_mm.x(), bin_size_mm.y()));
}

void check_bin_capacity(int objects, const BinCapacity& c) {
  if (objects <= c.parts) return;
  const double fraction_needed = objects * c.part_volume_mm3 / c.bin_volume_mm3;
  throw InputError(fmt::format(
      "--objects {}: the bin holds about {} (interior {:.3g} l at a packing fraction of {:g}, "
      "parts of {:.3g} cm^3 each; {} would fill {:.0f} % of the interior with solid "
      "material): use fewer --objects or a larger --bin-size W,D,H",
      objects, c.parts, c.bin_volume_mm3 * 1e-6, c.packing_fraction, c.part_volume_mm3 * 1e-3,
      objects, 100.0 * fraction_needed));
}

}  // namespace binpick
