#include "synth/physics/drop_layout.hpp"

#include <algorithm>
#include <string>

#include "host/core/error.hpp"

namespace binpick {
namespace {

// Start positions along one axis of the interior [-size/2, size/2], `inset` from either end.
std::vector<double> spread(int n, double size, double inset, const char* axis) {
  const double lo = -0.5 * size + inset, hi = 0.5 * size - inset;
  if (lo > hi)
    throw InputError("the part (bounding diameter " + std::to_string(2.0 * inset) +
                     " mm with clearance) is wider than the bin along " + axis);
  std::vector<double> at(n);
  for (int i = 0; i < n; ++i) at[i] = n == 1 ? 0.0 : lo + (hi - lo) * i / (n - 1);
  return at;
}

}  // namespace

std::vector<Eigen::Vector3d> wave_drop_positions(const DropOptions& options, int count,
                                                 double radius_mm, double lowest_centre_mm) {
  // Clearance keeps the collision margins of neighbours and walls from touching at release.
  const double clearance = 0.05 * radius_mm + 1.0;
  const double inset = radius_mm + clearance;
  const double spacing = 2.0 * radius_mm + clearance;
  const auto xs = spread(options.grid_x, options.bin_size_mm.x(), inset, "x");
  const auto ys = spread(options.grid_y, options.bin_size_mm.y(), inset, "y");
  const double base_z = std::max(options.drop_height_mm, lowest_centre_mm);

  std::vector<Eigen::Vector3d> positions;
  for (int k = 0; k < count; ++k) {
    Eigen::Vector3d p(xs[k % options.grid_x], ys[k / options.grid_x], base_z);
    for (bool moved = true; moved;) {
      moved = false;
      for (const auto& q : positions) {
        if ((p - q).norm() < spacing) {
          p.z() = q.z() + spacing;
          moved = true;
        }
      }
    }
    positions.push_back(p);
  }
  return positions;
}

}  // namespace binpick
