#include "host/detect/bin/bin_ground.hpp"

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

// The range [lo, hi] of `along` narrowed at an end that reaches the image's border (within the
// margin: [0, size)) past the bands of it (kBands of the range) where the samples are narrow
// across: their 5-95 % range in `across` (within [across_lo, across_hi]) under narrow_share of
// the bands' typical width (their 75 % quantile). A robot arm reaching out of a bin to the
// image's border stands above the ground too, and the window ran along it to the border, where
// the rim's side is not. The bin's own rows span it, wall to wall, and stop the walk. Only at
// the border: elsewhere the ends are a bin's walls, and a thin wall's column of samples, sparse
// under holes, is narrow too (docs/decisions/2026-12-02-bin-ground-arm-trim.md). Unchanged
// when less than min_kept of the range would be left.
void trim_narrow_ends(const std::vector<double>& along, const std::vector<double>& across,
                      double across_lo, double across_hi, double size, double& lo, double& hi,
                      const GroundOptions& opt) {
  constexpr int kBands = 50;
  const double step = (hi - lo) / kBands, reach = opt.margin * size;
  const bool at_lo = lo < reach, at_hi = hi >= size - 1 - reach;
  if (!(step > 0) || !(at_lo || at_hi)) return;
  std::vector<std::vector<double>> bands(kBands);
  for (std::size_t i = 0; i < along.size(); ++i)
    if (across[i] >= across_lo && across[i] <= across_hi && along[i] >= lo && along[i] <= hi)
      bands[std::min(kBands - 1, int((along[i] - lo) / step))].push_back(across[i]);
  std::vector<double> width(kBands, 0.0), widths;
  for (int k = 0; k < kBands; ++k)
    if (bands[k].size() >= 5) {
      width[k] = quantile(bands[k], 0.95) - quantile(bands[k], 0.05);
      widths.push_back(width[k]);
    }
  if (widths.empty()) return;
  const double narrow = opt.narrow_share * quantile(widths, 0.75);
  int a = 0, b = kBands - 1;
  while (at_lo && a < b && width[a] < narrow) ++a;
  while (at_hi && b > a && width[b] < narrow) --b;
  if (double(b - a + 1) < opt.min_kept * kBands) return;
  hi = lo + step * (b + 1);
  lo = lo + step * a;
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
    double u0 = quantile(u, 0.005), u1 = quantile(u, 0.995);
    double v0 = quantile(v, 0.005), v1 = quantile(v, 0.995);
    // Rows, then columns, then both again: an arm's columns are trimmed once its rows are off.
    for (int pass = 0; pass < 2; ++pass) {
      trim_narrow_ends(v, u, u0, u1, s.height, v0, v1, opt);
      trim_narrow_ends(u, v, v0, v1, s.width, u0, u1, opt);
    }
    const double mu = opt.margin * s.width, mv = opt.margin * s.height;
    PixelWindow w;
    w.u0 = std::uint32_t(std::max(0.0, u0 - mu));
    w.v0 = std::uint32_t(std::max(0.0, v0 - mv));
    w.u1 = std::uint32_t(std::ceil(std::min(double(s.width), u1 + mu + 1)));
    w.v1 = std::uint32_t(std::ceil(std::min(double(s.height), v1 + mv + 1)));
    const double area = double(w.u1 - w.u0) * double(w.v1 - w.v0);
    if (area > opt.max_area * double(s.width) * double(s.height)) return std::nullopt;
    return w;
  }
  return std::nullopt;
}

}  // namespace binpick
