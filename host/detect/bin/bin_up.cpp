#include "host/detect/bin/bin_up.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Geometry>

#include "host/core/angles.hpp"
#include "host/core/two_halves.hpp"

namespace binpick {
namespace {

struct Scored {
  Eigen::Vector3d up;
  std::size_t support = 0;
};

// Directions about `centre` (unit): centre + tan(a) b1 + tan(b) b2 normalised, a and b in
// [-span, span] in steps of `step` (degrees), those within max_tilt of the optical axis.
std::vector<Eigen::Vector3d> grid_about(const Eigen::Vector3d& centre, double span, double step,
                                        double max_tilt) {
  Eigen::Vector3d b1 = Eigen::Vector3d::UnitX() - centre.x() * centre;
  if (b1.norm() < 1e-6) b1 = Eigen::Vector3d::UnitY() - centre.y() * centre;
  b1.normalize();
  const Eigen::Vector3d b2 = centre.cross(b1);
  const int n = int(std::lround(span / step));
  std::vector<Eigen::Vector3d> dirs;
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j) {
      const Eigen::Vector3d d =
          (centre + std::tan(i * step * kDeg) * b1 + std::tan(j * step * kDeg) * b2).normalized();
      if (-d.z() >= std::cos(max_tilt * kDeg)) dirs.push_back(d);
    }
  return dirs;
}

// rim_support of every direction, half of them on a second thread (the device idles during
// the bin fit); the same values as one thread.
std::vector<Scored> score(const BorderBand& band, const std::vector<Eigen::Vector3d>& dirs,
                          double width) {
  std::vector<Scored> out(dirs.size());
  const auto run = [&](std::size_t first, std::size_t last) {
    for (std::size_t k = first; k < last; ++k) out[k] = {dirs[k], rim_support(band, dirs[k], width)};
  };
  in_two_halves(dirs.size(), run);
  return out;
}

// The `keep` best, each more than `apart` degrees from those kept before it (ties: grid order).
std::vector<Scored> best_apart(std::vector<Scored> scored, std::size_t keep, double apart) {
  std::stable_sort(scored.begin(), scored.end(),
                   [](const Scored& a, const Scored& b) { return a.support > b.support; });
  std::vector<Scored> kept;
  for (const Scored& s : scored) {
    if (kept.size() == keep || s.support == 0) break;
    const bool near = std::any_of(kept.begin(), kept.end(), [&](const Scored& k) {
      return k.up.dot(s.up) > std::cos(apart * kDeg);
    });
    if (!near) kept.push_back(s);
  }
  return kept;
}

}  // namespace

std::size_t rim_support(const BorderBand& band, const Eigen::Vector3d& up, double width) {
  const std::size_t n = band.points.size();
  if (n == 0 || !(width > 0)) return 0;
  const Eigen::Vector3f u = up.cast<float>();
  // Scratch reused between the thousands of calls of a search (one set per thread).
  thread_local std::vector<float> h;
  thread_local std::vector<std::array<std::uint32_t, 5>> c;
  h.resize(n);
  float lo = INFINITY, hi = -INFINITY;
  for (std::size_t i = 0; i < n; ++i) {
    h[i] = u.dot(band.points[i]);
    lo = std::min(lo, h[i]), hi = std::max(hi, h[i]);
  }
  // Bins 1 .. m hold the heights; 0 and m + 1 stay empty so that every bin has two neighbours.
  const std::size_t m = std::size_t((double(hi) - lo) / width) + 1;
  c.assign(m + 2, {0, 0, 0, 0, 0});  // count, then per side
  for (std::size_t i = 0; i < n; ++i) {
    std::array<std::uint32_t, 5>& b = c[std::min(m, std::size_t((h[i] - lo) / width)) + 1];
    ++b[0];
    for (int s = 0; s < 4; ++s) b[1 + s] += (band.sides[i] >> s) & 1u;
  }
  const auto sum = [&](std::size_t k, int col) { return c[k - 1][col] + c[k][col] + c[k + 1][col]; };
  std::uint32_t biggest = 0;
  for (std::size_t k = 1; k <= m; ++k) biggest = std::max(biggest, sum(k, 0));
  const double floor_count = std::max({0.03 * biggest, 0.01 * double(n), 20.0});
  for (std::size_t k = m; k >= 1; --k) {
    const std::uint32_t here = sum(k, 0);
    const bool peak = here >= sum(k - 1 > 0 ? k - 1 : k, 0) && (k == m || here > sum(k + 1, 0));
    if (!peak || here < floor_count) continue;
    const double side_need = std::max(5.0, 0.05 * here);
    int covered = 0;
    for (int s = 0; s < 4; ++s) covered += sum(k, 1 + s) >= side_need;
    if (covered >= 3) {
      std::uint32_t above = 0;
      for (std::size_t j = k + 2; j <= m; ++j) above += c[j][0];
      return here > 2 * above ? here - 2 * above : 0;
    }
  }
  return 0;
}

std::optional<RimUp> search_rim_up(const PlaneSamples& s, const RimUpSearch& opt) {
  const BorderBand all = border_band(s, opt.band, 1, false);
  if (all.points.size() < 50) return std::nullopt;
  // The band's reach across the optical axis: a direction e off up moves heights by up to
  // reach * e, which sets the coarse steps' bin widths.
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : all.points) mean += p.head<2>().cast<double>();
  mean /= double(all.points.size());
  std::vector<double> r;
  for (const auto& p : all.points) r.push_back((p.head<2>().cast<double>() - mean).norm());
  std::nth_element(r.begin(), r.begin() + std::ptrdiff_t(0.95 * double(r.size() - 1)), r.end());
  const double reach = r[std::size_t(0.95 * double(r.size() - 1))];
  // The coarse steps need fewer samples: a few thousand hold the rim's hundreds.
  const auto thinned = [&](std::size_t at_most) {
    const std::size_t stride = std::max<std::size_t>(1, all.points.size() / at_most);
    return border_band(s, opt.band, stride, false);
  };
  const BorderBand coarse = thinned(2000), middle = thinned(6000), fine = thinned(12000);
  struct Level {
    const BorderBand* band;
    double step, span;  // degrees; span 0: the whole cap about the optical axis
    std::size_t keep;
  };
  const Level levels[] = {{&coarse, 2.0, 0.0, 4}, {&middle, 0.5, 2.0, 2}, {&fine, 0.125, 0.5, 1}};
  std::vector<Scored> seeds = {{Eigen::Vector3d(0, 0, -1), 0}};
  for (const Level& level : levels) {
    const double width =
        std::max(opt.tol, reach * std::sin(level.step / 2 * kDeg));
    std::vector<Eigen::Vector3d> dirs;
    for (const Scored& seed : seeds) {
      const double span = level.span > 0 ? level.span : opt.max_tilt_deg;
      const std::vector<Eigen::Vector3d> g = grid_about(seed.up, span, level.step, opt.max_tilt_deg);
      dirs.insert(dirs.end(), g.begin(), g.end());
    }
    seeds = best_apart(score(*level.band, dirs, width), level.keep, 2 * level.step);
    if (seeds.empty()) return std::nullopt;
  }
  return RimUp{seeds[0].up, seeds[0].support};
}

}  // namespace binpick
