#include "host/detect/bin/bin_floor.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "host/detect/bin/bin_rim.hpp"

namespace binpick {

FloorUnder floor_under(const PlaneSamples& s, const std::vector<FoundPlane>& planes,
                       const Eigen::Vector3d& up, const Eigen::Vector3d& a1,
                       const Eigen::Vector3d& a2, const std::array<double, 4>& edge,
                       double rim_height, double tol, double noise) {
  FloorUnder f;
  for (const auto& p : s.points)
    if (in_frame(a1, a2, edge, p.cast<double>())) f.heights.push_back(up.dot(p.cast<double>()));
  std::sort(f.heights.begin(), f.heights.end());
  const std::vector<double>& h = f.heights;
  const std::size_t allowed_below = std::max<std::size_t>(20, h.size() / 500);
  const double gap = std::max(3 * tol, 4 * noise);
  std::size_t most = 0;
  for (const FoundPlane& p : planes) {
    if (p.normal.dot(up) < std::cos(5 * std::numbers::pi / 180)) continue;
    double sum = 0;
    std::size_t count = 0;
    for (std::uint32_t i : p.inliers) {
      const Eigen::Vector3d q = s.points[i].cast<double>();
      if (!in_frame(a1, a2, edge, q)) continue;
      sum += up.dot(q);
      ++count;
    }
    const double height = count ? sum / double(count) : 0.0;
    if (count < 50 || count <= most || height > rim_height - 3 * tol) continue;
    const auto under = std::lower_bound(h.begin(), h.end(), height - gap) - h.begin();
    if (std::size_t(under) > allowed_below) continue;
    most = count;
    f.plane = height;
  }
  return f;
}

}  // namespace binpick
