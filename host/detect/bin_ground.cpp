#include "host/detect/bin_ground.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "host/core/quantile.hpp"

namespace binpick {
namespace {

// Signed height of a sample over the plane (the normal faces the camera: up is n).
double over(const FoundPlane& p, const Eigen::Vector3f& x) {
  return p.normal.dot(x.cast<double>()) + p.d;
}

bool is_ground(const PlaneSamples& s, const FoundPlane& p, const GroundOptions& opt) {
  const double rw = opt.ring * s.width, rh = opt.ring * s.height;
  std::array<std::size_t, 4> in_ring{}, on_plane{};
  std::size_t below = 0;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const double h = over(p, s.points[i]);
    below += h < -2 * opt.tol;
    const bool side[4] = {s.u[i] < rw, s.u[i] >= s.width - rw, s.v[i] < rh,
                          s.v[i] >= s.height - rh};
    for (int b = 0; b < 4; ++b)
      if (side[b]) ++in_ring[b], on_plane[b] += std::abs(h) <= 2 * opt.tol;
  }
  if (double(below) > opt.max_below * double(s.points.size())) return false;
  // A side without depth in its ring (beyond the ground's end, or not lit) says nothing.
  int on_ground = 0;
  for (int b = 0; b < 4; ++b) {
    if (in_ring[b] < 10) continue;
    if (double(on_plane[b]) < opt.ring_share * double(in_ring[b])) return false;
    ++on_ground;
  }
  return on_ground >= 3;
}

}  // namespace

std::optional<PixelWindow> window_above_ground(const PlaneSamples& s,
                                               const std::vector<FoundPlane>& planes,
                                               const GroundOptions& opt) {
  for (const FoundPlane& p : planes) {
    if (!is_ground(s, p, opt)) continue;
    std::vector<double> u, v;
    for (std::size_t i = 0; i < s.points.size(); ++i)
      if (over(p, s.points[i]) > 3 * opt.tol) u.push_back(s.u[i]), v.push_back(s.v[i]);
    if (u.size() < 100) return std::nullopt;
    const double mu = opt.margin * s.width, mv = opt.margin * s.height;
    const auto lo = [&](const std::vector<double>& x, double m) {
      return std::max(0.0, quantile(x, 0.005) - m);
    };
    const auto hi = [&](const std::vector<double>& x, double m, std::uint32_t size) {
      return std::min(double(size), quantile(x, 0.995) + m + 1);
    };
    PixelWindow w;
    w.u0 = std::uint32_t(lo(u, mu));
    w.v0 = std::uint32_t(lo(v, mv));
    w.u1 = std::uint32_t(std::ceil(hi(u, mu, s.width)));
    w.v1 = std::uint32_t(std::ceil(hi(v, mv, s.height)));
    const double area = double(w.u1 - w.u0) * double(w.v1 - w.v0);
    if (area > opt.max_area * double(s.width) * double(s.height)) return std::nullopt;
    return w;
  }
  return std::nullopt;
}

}  // namespace binpick
