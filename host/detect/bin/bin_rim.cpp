#include "host/detect/bin/bin_rim.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "host/core/quantile.hpp"
#include "host/core/two_halves.hpp"

namespace binpick {
namespace {

struct Histogram {
  double lo = 0, width = 1;
  std::vector<double> count;
  int bin(double x) const { return int(std::floor((x - lo) / width)); }
  double left(int k) const { return lo + width * k; }
};

Histogram histogram(const std::vector<double>& xs, double width) {
  Histogram h;
  h.width = width;
  if (xs.empty()) return h;
  const auto [mn, mx] = std::minmax_element(xs.begin(), xs.end());
  h.lo = *mn - width;
  h.count.assign(std::size_t((*mx - h.lo) / width) + 2, 0.0);
  for (double x : xs) h.count[std::size_t(h.bin(x))] += 1;
  return h;
}

// The sum of the squared counts of histogram(xs, width), without building it: the same bins,
// and the counts are integers whose squares add up exactly in any order, so the same value.
// counts: scratch, reused between calls.
double histogram_sharpness(const std::vector<double>& xs, double width,
                           std::vector<std::uint32_t>& counts) {
  if (xs.empty()) return 0;
  const auto [mn, mx] = std::minmax_element(xs.begin(), xs.end());
  const double lo = *mn - width;
  counts.assign(std::size_t((*mx - lo) / width) + 2, 0);
  for (double x : xs) ++counts[std::size_t(int(std::floor((x - lo) / width)))];
  std::uint64_t sum = 0;
  for (std::uint32_t c : counts) sum += std::uint64_t(c) * c;
  return double(sum);
}

// The frame's two sides along one axis: the inner edge of each, and whether it is there.
struct Sides {
  bool lo_seen = false, hi_seen = false;
  double lo = 0, hi = 0;
  double mid = 0;  // the split between the two sides
};

// share: a side's bins hold at least this fraction of its peak; gap: empty bins allowed (0, 1);
// judge: a side must stand out of the median count (only where the other axis' sides spread
// evenly over the histogram, i.e. in the coarse pass). mid: the split between the sides, NaN to
// take the middle of the points (the fine pass takes the coarse one's: with a side out of view
// its own middle would split the other side).
Sides find_sides(const std::vector<double>& xs, double width, double half_spacing, double share,
                 int gap, bool judge, double mid) {
  Sides out;
  if (xs.size() < 10) return out;
  const Histogram h = histogram(xs, width);
  if (std::isnan(mid)) mid = 0.5 * (quantile(xs, 0.02) + quantile(xs, 0.98));
  out.mid = mid;
  const int n = int(h.count.size()), m = std::clamp(h.bin(mid), 0, n - 1);
  std::vector<double> nonzero;
  for (double c : h.count)
    if (c > 0) nonzero.push_back(c);
  const double background = quantile(nonzero, 0.5);
  int lo = 0, hi = n - 1;
  for (int k = 0; k <= m && k < n; ++k)
    if (h.count[k] > h.count[lo]) lo = k;
  for (int k = n - 1; k > m && k >= 0; --k)
    if (h.count[k] > h.count[hi]) hi = k;
  const auto real = [&](int k) {
    return h.count[k] >= std::max(3.0, judge ? 4.0 * background : 0.0);
  };
  out.lo_seen = lo < m && real(lo);
  out.hi_seen = hi > m && real(hi);
  // Walk inward over a side's bins (a gap allowed: the samples are about a bin apart, and an
  // oblique rim is sparse); the edge is the innermost point of the run.
  if (out.lo_seen) {
    const double thr = std::max(1.0, share * h.count[lo]);
    int a = lo;
    while (true) {
      if (a + 1 < m && h.count[a + 1] >= thr) ++a;
      else if (gap > 0 && a + 2 < m && h.count[a + 2] >= thr) a += 2;
      else break;
    }
    out.lo = h.left(lo);
    for (double x : xs)
      if (h.bin(x) >= lo && h.bin(x) <= a) out.lo = std::max(out.lo, x);
    // The true edge lies between the innermost sample and the next one inward, which is not
    // on the rim: half a sample spacing in, on average.
    out.lo += half_spacing;
  }
  if (out.hi_seen) {
    const double thr = std::max(1.0, share * h.count[hi]);
    int b = hi;
    while (true) {
      if (b - 1 > m && h.count[b - 1] >= thr) --b;
      else if (gap > 0 && b - 2 > m && h.count[b - 2] >= thr) b -= 2;
      else break;
    }
    out.hi = h.left(hi + 1);
    for (double x : xs)
      if (h.bin(x) >= b && h.bin(x) <= hi) out.hi = std::min(out.hi, x);
    out.hi -= half_spacing;
  }
  return out;
}

}  // namespace

BorderBand border_band(const PlaneSamples& s, double band, std::size_t stride, bool outside) {
  BorderBand out;
  const PixelWindow w = s.window.u1 ? s.window : PixelWindow{0, 0, s.width, s.height};
  const double bw = band * (w.u1 - w.u0), bh = band * (w.v1 - w.v0);
  std::size_t seen = 0;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const bool in_window = s.u[i] >= w.u0 && s.u[i] < w.u1 && s.v[i] >= w.v0 && s.v[i] < w.v1;
    if (!outside && !in_window) continue;
    const int sides = (s.u[i] < w.u0 + bw ? 1 : 0) | (s.u[i] >= w.u1 - bw ? 2 : 0) |
                      (s.v[i] < w.v0 + bh ? 4 : 0) | (s.v[i] >= w.v1 - bh ? 8 : 0);
    if (!sides || seen++ % stride != 0) continue;
    out.index.push_back(i);
    out.points.push_back(s.points[i]);
    out.sides.push_back(std::uint8_t(sides));
  }
  return out;
}

std::size_t samples_above(const BorderBand& band, const Eigen::Vector3d& up, double height,
                          bool one_side_may_be_covered) {
  std::size_t above = 0;
  std::array<std::size_t, 4> per_side{};
  for (std::size_t i = 0; i < band.points.size(); ++i) {
    if (!(up.dot(band.points[i].cast<double>()) > height)) continue;
    ++above;
    for (int b = 0; b < 4; ++b) per_side[b] += (band.sides[i] >> b) & 1;
  }
  // A sample is counted once on each side it belongs to: those off the most covered side are
  // all the others.
  return one_side_may_be_covered ? above - *std::max_element(per_side.begin(), per_side.end())
                                 : above;
}

RimFit fit_rim(const PlaneSamples& s, const Eigen::Vector3d& up, const Eigen::Vector3d& e1,
               const Eigen::Vector3d& e2, const RimOptions& opt) {
  RimFit rim;
  const BorderBand border = border_band(s, opt.band, 1, false);
  const std::vector<std::size_t>& band = border.index;
  std::vector<double> heights;
  for (std::size_t i : band) heights.push_back(up.dot(s.points[i].cast<double>()));
  if (band.size() < 50) {
    rim.why = "too few points with depth along the image border";
    return rim;
  }
  const Histogram h = histogram(heights, opt.tol);
  const int n = int(h.count.size());
  std::vector<double> smooth(n, 0);
  for (int k = 0; k < n; ++k)
    for (int j = std::max(0, k - 1); j <= std::min(n - 1, k + 1); ++j) smooth[k] += h.count[j];
  const double biggest = *std::max_element(smooth.begin(), smooth.end());
  // A low bar (the ground around a bin can hold most of the border): the sides test decides.
  const double floor_count = std::max({0.03 * biggest, 0.01 * double(band.size()), 20.0});
  std::vector<std::size_t> on_rim;
  for (int k = n - 1; k >= 0 && !rim.found; --k) {
    const bool peak = (k == 0 || smooth[k] >= smooth[k - 1]) &&
                      (k == n - 1 || smooth[k] > smooth[k + 1]);
    if (!peak || smooth[k] < floor_count) continue;
    const double centre = h.left(k) + 0.5 * h.width;
    on_rim.clear();
    double sum = 0;
    int sides[4] = {0, 0, 0, 0};
    for (std::size_t j = 0; j < band.size(); ++j)
      if (std::abs(heights[j] - centre) <= 1.5 * opt.tol) {
        on_rim.push_back(band[j]);
        sum += heights[j];
        for (int b = 0; b < 4; ++b) sides[b] += (border.sides[j] >> b) & 1;
      }
    const double side_need = std::max(5.0, 0.05 * double(on_rim.size()));
    int covered = 0;
    for (int b = 0; b < 4; ++b) covered += sides[b] >= side_need;
    if (covered < 3) continue;
    rim.found = true;
    rim.height = sum / double(on_rim.size());
    rim.points = on_rim.size();
    rim.samples = on_rim;
  }
  if (!rim.found) {
    rim.why = "no structure at one height runs along three sides of the image border";
    return rim;
  }

  std::vector<double> x(on_rim.size()), y(on_rim.size());
  for (std::size_t j = 0; j < on_rim.size(); ++j) {
    const Eigen::Vector3d p = s.points[on_rim[j]].cast<double>();
    x[j] = e1.dot(p), y[j] = e2.dot(p);
  }
  const double width = std::max(opt.tol, 4.0);
  // The frame's angle: the half-degree step whose two axes' histograms are sharpest (the first
  // among equals). Every fourth step first, then every step within kNearSteps of the kTopCoarse
  // best of those: a frame's sharpness falls off steadily on both sides of its angle (a side
  // of length L spreads over L sin(turn) / width bins), so its best step lies near a good
  // coarse one, and at most 63 steps of the 180 are scored. The steps scored are independent: half
  // of them on a second thread (the device idles during the bin fit), the choice in step order.
  constexpr int kSteps = 180, kCoarseEvery = 4, kTopCoarse = 3, kNearSteps = 3;
  const auto angle = [](int step) { return step * 0.5 * std::numbers::pi / 180.0; };
  std::vector<double> scores(kSteps, -1.0);  // -1: not scored (a score is a sum of squares)
  const auto score_steps = [&](const std::vector<int>& steps) {
    in_two_halves(steps.size(), [&](std::size_t first, std::size_t last) {
      std::vector<double> xr(x.size()), yr(y.size());
      std::vector<std::uint32_t> counts;
      for (std::size_t i = first; i < last; ++i) {
        const int step = steps[i];
        const double a = angle(step), c = std::cos(a), sn = std::sin(a);
        for (std::size_t j = 0; j < x.size(); ++j) xr[j] = c * x[j] + sn * y[j], yr[j] = -sn * x[j] + c * y[j];
        scores[std::size_t(step)] = histogram_sharpness(xr, width, counts) + histogram_sharpness(yr, width, counts);
      }
    });
  };
  std::vector<int> coarse;
  for (int step = 0; step < kSteps; step += kCoarseEvery) coarse.push_back(step);
  score_steps(coarse);
  std::vector<int> top = coarse;
  std::stable_sort(top.begin(), top.end(), [&](int a, int b) {
    return scores[std::size_t(a)] > scores[std::size_t(b)];
  });
  top.resize(kTopCoarse);
  std::vector<int> near;
  for (int t : top)
    for (int d = -kNearSteps; d <= kNearSteps; ++d) {
      const int step = (t + d + kSteps) % kSteps;  // the turn wraps: 90 degrees is 0 again
      if (scores[std::size_t(step)] < 0 && std::find(near.begin(), near.end(), step) == near.end())
        near.push_back(step);
    }
  score_steps(near);
  double best = -1;
  int best_step = 0;
  for (int step = 0; step < kSteps; ++step)
    if (scores[std::size_t(step)] > best) best = scores[std::size_t(step)], best_step = step;
  rim.angle = angle(best_step);
  std::vector<double> xr(x.size()), yr(y.size());
  const double c = std::cos(rim.angle), sn = std::sin(rim.angle);
  for (std::size_t j = 0; j < x.size(); ++j) xr[j] = c * x[j] + sn * y[j], yr[j] = -sn * x[j] + c * y[j];
  // Coarse sides first; then each side's edge from the points off the other axis' sides (a
  // corner's points belong to both, and the other sides' points run up to the edge).
  Sides cx = find_sides(xr, width, 0.0, 0.3, 0, true, NAN),
        cy = find_sides(yr, width, 0.0, 0.3, 0, true, NAN);
  // With the camera tilted far, the near side of the rim may be all there is at its height:
  // along the axis across it the points then form one band, no wider than a quarter of their
  // spread along it, and the coarse pass, which asks a side to stand out of the rest, sees
  // nothing. The band is then the side away from which the points below the rim lie.
  const double spread_x = quantile(xr, 0.98) - quantile(xr, 0.02),
               spread_y = quantile(yr, 0.98) - quantile(yr, 0.02);
  const auto one_band = [&](const std::vector<double>& along, double spread, double spread_other,
                            const Eigen::Vector3d& axis, Sides& sides) {
    if (sides.lo_seen || sides.hi_seen || !(spread < 0.25 * spread_other)) return false;
    std::vector<double> below;
    for (const Eigen::Vector3f& pf : s.points) {
      const Eigen::Vector3d p = pf.cast<double>();
      if (up.dot(p) < rim.height - 3 * opt.tol) below.push_back(axis.dot(p));
    }
    if (below.size() < 20) return false;
    const double lo = quantile(along, 0.02), hi = quantile(along, 0.98);
    const double inside = quantile(below, 0.5);
    if (inside > hi) sides.lo_seen = true, sides.lo = quantile(along, 1.0);
    else if (inside < lo) sides.hi_seen = true, sides.hi = quantile(along, 0.0);
    else return false;
    sides.mid = 0.5 * (lo + hi);
    return true;
  };
  const Eigen::Vector3d a1 = c * e1 + sn * e2, a2 = up.cross(a1);
  const bool band_x = one_band(xr, spread_x, spread_y, a1, cx),
             band_y = one_band(yr, spread_y, spread_x, a2, cy);
  const auto off = [&](const Sides& other, double v) {
    return (!other.lo_seen || v > other.lo + width) && (!other.hi_seen || v < other.hi - width);
  };
  std::vector<double> xs, ys, depth;
  for (std::size_t j = 0; j < x.size(); ++j) {
    if (off(cy, yr[j])) xs.push_back(xr[j]);
    if (off(cx, xr[j])) ys.push_back(yr[j]);
  }
  for (std::size_t i : on_rim) depth.push_back(s.points[i].z());
  const double spacing = opt.focal > 0 ? s.stride * quantile(depth, 0.5) / opt.focal : 0.0;
  // A band's inner edge is its innermost point (a fine pass would split it at its middle),
  // moved in by half a sample spacing as find_sides does.
  Sides fx = band_x ? cx : find_sides(xs, width, 0.5 * spacing, 0.05, 1, false, cx.mid);
  Sides fy = band_y ? cy : find_sides(ys, width, 0.5 * spacing, 0.05, 1, false, cy.mid);
  for (Sides* f : {band_x ? &fx : nullptr, band_y ? &fy : nullptr})
    if (f) f->lo_seen ? f->lo += 0.5 * spacing : f->hi -= 0.5 * spacing;
  rim.edge = {fx.lo, fx.hi, fy.lo, fy.hi};
  // A side counts when both passes saw it.
  rim.seen = {cx.lo_seen && fx.lo_seen, cx.hi_seen && fx.hi_seen, cy.lo_seen && fy.lo_seen,
              cy.hi_seen && fy.hi_seen};
  // A side on at least one axis. With the camera tilted far, the near side may be all that
  // stands out: the far side is beyond the image and the two others are slivers at its border,
  // no denser than the near side's own points along that axis (bin_fit.cpp then takes the
  // interior to the farthest points seen below the rim along the axis without a side).
  if (!(rim.seen[0] || rim.seen[1]) && !(rim.seen[2] || rim.seen[3])) {
    rim.found = false;
    rim.why = "the structure at the rim's height is not a rectangular frame";
  }
  return rim;
}

std::optional<Eigen::Vector3d> rim_normal(const PlaneSamples& s, const RimFit& rim,
                                          const Eigen::Vector3d& up, double tol,
                                          double min_spread) {
  if (rim.samples.size() < 100) return std::nullopt;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t i : rim.samples) mean += s.points[i].cast<double>();
  mean /= double(rim.samples.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (std::size_t i : rim.samples) {
    const Eigen::Vector3d d = s.points[i].cast<double>() - mean;
    cov += d * d.transpose();
  }
  cov /= double(rim.samples.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);  // ascending eigenvalues
  Eigen::Vector3d n = eig.eigenvectors().col(0);
  if (n.dot(up) < 0) n = -n;
  const bool spread = std::sqrt(std::max(0.0, eig.eigenvalues()(1))) > min_spread * tol;
  const bool flat = std::sqrt(std::max(0.0, eig.eigenvalues()(0))) <= tol;
  const bool near = n.dot(up) >= std::cos(10 * std::numbers::pi / 180);
  if (!(spread && flat && near)) return std::nullopt;
  return n;
}

double share_inside(const PlaneSamples& s, const Eigen::Vector3d& up, const Eigen::Vector3d& a1,
                    const Eigen::Vector3d& a2, double height, const std::array<double, 4>& edge,
                    double tol) {
  std::size_t level = 0, inside = 0;
  for (const Eigen::Vector3f& pf : s.points) {
    const Eigen::Vector3d p = pf.cast<double>();
    if (std::abs(up.dot(p) - height) > 1.5 * tol) continue;
    ++level;
    const double q1 = a1.dot(p), q2 = a2.dot(p);
    inside += q1 > edge[0] + 2 * tol && q1 < edge[1] - 2 * tol && q2 > edge[2] + 2 * tol &&
              q2 < edge[3] - 2 * tol;
  }
  return level ? double(inside) / double(level) : 0.0;
}

}  // namespace binpick
