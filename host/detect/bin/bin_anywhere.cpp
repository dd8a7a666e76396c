#include "host/detect/bin/bin_anywhere.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "host/core/angles.hpp"
#include "host/core/quantile.hpp"

namespace binpick {
namespace {

// The sample coordinates in the plane across up (a, b) and along it (h).
struct Projected {
  std::vector<double> a, b, h;
};

// A candidate rectangle: a slice, a turn, the centre in the turned axes (u along W, v along D).
struct Candidate {
  double score = 0;
  double height = 0;  // the slice's middle
  double turn = 0;    // radians: u = cos a + sin b
  double cu = 0, cv = 0;
};

// Line-ness of a histogram: each bin (3 wide) over the larger of its neighbours a strip width
// away on either side, so a strip of points stands out and an even spread (the ground) does not.
std::vector<double> strip_response(const std::vector<int>& hist, int away) {
  const int n = int(hist.size());
  const auto at = [&](int i) { return i >= 0 && i < n ? hist[std::size_t(i)] : 0; };
  std::vector<double> f(hist.size(), 0.0);
  for (int i = 0; i < n; ++i) {
    const int here = at(i - 1) + at(i) + at(i + 1);
    const int aside = std::max(at(i - away - 1) + at(i - away) + at(i - away + 1),
                               at(i + away - 1) + at(i + away) + at(i + away + 1));
    f[std::size_t(i)] = std::max(0, here - aside);
  }
  return f;
}

// The best pair of strips `span` .. `span + extra` bins apart: min of the two responses (both
// sides must show), and the middle between them (bins from the start).
std::pair<double, double> best_pair(const std::vector<double>& f, int span, int extra) {
  double best = 0, middle = 0;
  const int n = int(f.size());
  for (int i = 0; i < n; ++i) {
    if (f[std::size_t(i)] <= best) continue;
    for (int s = span; s <= span + extra && i + s < n; ++s) {
      const double m = std::min(f[std::size_t(i)], f[std::size_t(i + s)]);
      if (m > best) best = m, middle = i + 0.5 * s;
    }
  }
  return {best, middle};
}

// The turned coordinates of point i.
inline Eigen::Vector2d turned(const Projected& p, std::size_t i, double c, double s) {
  return {c * p.a[i] + s * p.b[i], -s * p.a[i] + c * p.b[i]};
}

// The strip's samples about a candidate (within tol of its height, in a band outside the inner
// edges), by side: 0 +u, 1 -u, 2 +v, 3 -v.
std::array<std::vector<std::size_t>, 4> strip_sides(const Projected& p, const Candidate& c,
                                                   const SizedRimSearch& opt) {
  std::array<std::vector<std::size_t>, 4> sides;
  const double co = std::cos(c.turn), si = std::sin(c.turn);
  const double hw = 0.5 * opt.size.x(), hd = 0.5 * opt.size.y(), in = 2 * opt.tol,
               out = opt.strip + 2 * opt.tol;
  for (std::size_t i = 0; i < p.h.size(); ++i) {
    if (std::abs(p.h[i] - c.height) > opt.tol) continue;
    const Eigen::Vector2d q = turned(p, i, co, si) - Eigen::Vector2d(c.cu, c.cv);
    const double du = std::abs(q.x()) - hw, dv = std::abs(q.y()) - hd;
    if (du > -in && du < out && std::abs(q.y()) < hd + out) sides[q.x() > 0 ? 0 : 1].push_back(i);
    else if (dv > -in && dv < out && std::abs(q.x()) < hw + out) sides[q.y() > 0 ? 2 : 3].push_back(i);
  }
  return sides;
}

// Refines a candidate from its strips: the turn from each side's direction (least squares), the
// centre midway between opposite strips' medians, the height their median; twice.
void refine(const Projected& p, Candidate& c, const SizedRimSearch& opt) {
  for (int pass = 0; pass < 2; ++pass) {
    const auto sides = strip_sides(p, c, opt);
    // The turn: each side's points give the direction of least spread across it.
    double sin_sum = 0, cos_sum = 0;
    for (int k = 0; k < 4; ++k) {
      if (sides[std::size_t(k)].size() < 10) continue;
      Eigen::Vector2d mean = Eigen::Vector2d::Zero();
      for (std::size_t i : sides[std::size_t(k)]) mean += Eigen::Vector2d(p.a[i], p.b[i]);
      mean /= double(sides[std::size_t(k)].size());
      Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
      for (std::size_t i : sides[std::size_t(k)]) {
        const Eigen::Vector2d d = Eigen::Vector2d(p.a[i], p.b[i]) - mean;
        cov += d * d.transpose();
      }
      // The side's direction, as an angle of the u axis (sides along v run along u's normal).
      const double along = 0.5 * std::atan2(2 * cov(0, 1), cov(0, 0) - cov(1, 1));
      const double turn_k = k < 2 ? along - 0.5 * std::numbers::pi : along;
      const double w = double(sides[std::size_t(k)].size());
      // Angles modulo 90 degrees (4 x) averaged on the circle, near the current turn.
      sin_sum += w * std::sin(4 * (turn_k - c.turn));
      cos_sum += w * std::cos(4 * (turn_k - c.turn));
    }
    if (cos_sum > 0) c.turn += 0.25 * std::atan2(sin_sum, cos_sum);
    const auto again = strip_sides(p, c, opt);
    const double co = std::cos(c.turn), si = std::sin(c.turn);
    std::array<double, 4> median{};
    std::array<bool, 4> has{};
    std::vector<double> heights;
    for (int k = 0; k < 4; ++k) {
      std::vector<double> x;
      for (std::size_t i : again[std::size_t(k)]) {
        const Eigen::Vector2d q = turned(p, i, co, si);
        x.push_back(k < 2 ? q.x() : q.y());
        heights.push_back(p.h[i]);
      }
      has[std::size_t(k)] = x.size() >= 5;
      if (has[std::size_t(k)]) median[std::size_t(k)] = quantile(x, 0.5);
    }
    if (has[0] && has[1]) c.cu = 0.5 * (median[0] + median[1]);
    if (has[2] && has[3]) c.cv = 0.5 * (median[2] + median[3]);
    if (heights.size() >= 10) c.height = quantile(heights, 0.5);
  }
}

// Share of the perimeter's segments (10 a side) the strip reaches, and its samples.
std::pair<double, std::size_t> coverage(const Projected& p, const Candidate& c,
                                        const SizedRimSearch& opt) {
  const auto sides = strip_sides(p, c, opt);
  const double co = std::cos(c.turn), si = std::sin(c.turn);
  constexpr int kSegments = 10;
  int reached = 0;
  std::size_t points = 0;
  for (int k = 0; k < 4; ++k) {
    std::array<bool, kSegments> seg{};
    const double half = k < 2 ? 0.5 * opt.size.y() : 0.5 * opt.size.x();
    for (std::size_t i : sides[std::size_t(k)]) {
      const Eigen::Vector2d q = turned(p, i, co, si) - Eigen::Vector2d(c.cu, c.cv);
      const double along = k < 2 ? q.y() : q.x();
      const int j = int(std::floor((along + half) / (2 * half) * kSegments));
      if (j >= 0 && j < kSegments) seg[std::size_t(j)] = true;
    }
    reached += int(std::count(seg.begin(), seg.end(), true));
    points += sides[std::size_t(k)].size();
  }
  return {double(reached) / (4 * kSegments), points};
}

// How much denser the strip is than the bands just inside and just outside it (kBand wide), at
// its height: a rim stands alone at its height, while a slice through the ground or a heap is as
// dense beside the "strip" as on it.
double strip_contrast(const Projected& p, const Candidate& c, const SizedRimSearch& opt) {
  constexpr double kBand = 50;
  const double co = std::cos(c.turn), si = std::sin(c.turn);
  const double hw = 0.5 * opt.size.x(), hd = 0.5 * opt.size.y(), in = 2 * opt.tol,
               out = opt.strip + 2 * opt.tol;
  std::size_t strip = 0, beside = 0;
  for (std::size_t i = 0; i < p.h.size(); ++i) {
    if (std::abs(p.h[i] - c.height) > opt.tol) continue;
    const Eigen::Vector2d q = turned(p, i, co, si) - Eigen::Vector2d(c.cu, c.cv);
    // Signed distance outside the inner rectangle (negative inside), along the nearer axis.
    const double du = std::abs(q.x()) - hw, dv = std::abs(q.y()) - hd;
    const double d = std::max(du, dv);
    if (std::abs(q.x()) > hw + out + kBand || std::abs(q.y()) > hd + out + kBand) continue;
    if (d > -in && d < out) ++strip;
    else if ((d > -in - kBand && d <= -in) || (d >= out && d < out + kBand)) ++beside;
  }
  const double strip_width = out + in, beside_width = 2 * kBand;
  return (double(strip) / strip_width) / (double(std::max<std::size_t>(beside, 1)) / beside_width);
}

// Of the samples inside the rectangle (2 tol in from its inner edges): the share at the rim's
// height (a layer of parts or a table top there is no frame) and the share above it by more
// than 2 tol (a contour through a heap, whose inside stands higher, is no rim: what a bin holds
// lies below its rim).
std::pair<double, double> inside_shares(const Projected& p, const Candidate& c,
                                        const SizedRimSearch& opt) {
  const double co = std::cos(c.turn), si = std::sin(c.turn);
  std::size_t at = 0, above = 0, inside = 0, slice = 0;
  for (std::size_t i = 0; i < p.h.size(); ++i) {
    const Eigen::Vector2d q = turned(p, i, co, si) - Eigen::Vector2d(c.cu, c.cv);
    const bool in = std::abs(q.x()) < 0.5 * opt.size.x() - 2 * opt.tol &&
                    std::abs(q.y()) < 0.5 * opt.size.y() - 2 * opt.tol;
    const bool level = std::abs(p.h[i] - c.height) <= opt.tol;
    slice += level;
    if (!in) continue;
    ++inside;
    at += level;
    above += p.h[i] > c.height + 2 * opt.tol;
  }
  return {slice ? double(at) / double(slice) : 1.0,
          inside ? double(above) / double(inside) : 1.0};
}

// The best candidates of one up: every slice with enough samples, every turn.
std::vector<Candidate> candidates_at(const Projected& p, const SizedRimSearch& opt) {
  std::vector<Candidate> best;
  constexpr std::size_t kKeep = 8;
  const double lo = quantile(p.h, 0.001), hi = quantile(p.h, 0.999);
  const int slices = int(std::ceil((hi - lo) / opt.tol)) + 1;
  if (slices <= 0 || slices > 100000) return best;
  std::vector<std::vector<std::size_t>> in(std::size_t(slices) + 1);
  for (std::size_t i = 0; i < p.h.size(); ++i) {
    const int k = int(std::floor((p.h[i] - lo) / opt.tol));
    if (k < 0 || k >= slices) continue;
    in[std::size_t(k)].push_back(i);
    if (k > 0) in[std::size_t(k - 1)].push_back(i);  // slice j: [lo + j tol, lo + (j + 2) tol)
  }
  const int away = std::max(2, int(std::lround(2 * opt.tol / opt.cell)) + 2);
  const int extra = int(std::ceil(opt.strip / opt.cell));
  for (int j = 0; j < slices; ++j) {
    const std::vector<std::size_t>& idx = in[std::size_t(j)];
    if (idx.size() < opt.min_slice) continue;
    for (double deg = 0; deg < 180; deg += opt.turn_step_deg) {
      const double t = deg * kDeg, co = std::cos(t), si = std::sin(t);
      std::vector<double> u, v;
      u.reserve(idx.size()), v.reserve(idx.size());
      for (std::size_t i : idx) {
        const Eigen::Vector2d q = turned(p, i, co, si);
        u.push_back(q.x()), v.push_back(q.y());
      }
      const auto [u0, u1] = std::minmax_element(u.begin(), u.end());
      const auto [v0, v1] = std::minmax_element(v.begin(), v.end());
      if (*u1 - *u0 < opt.size.x() || *v1 - *v0 < opt.size.y()) continue;  // too small
      const auto histogram = [&](const std::vector<double>& x, double x0, double x1) {
        std::vector<int> h(std::size_t((x1 - x0) / opt.cell) + 1, 0);
        for (double xi : x) ++h[std::size_t((xi - x0) / opt.cell)];
        return h;
      };
      const auto [su, mu] = best_pair(strip_response(histogram(u, *u0, *u1), away),
                                      int(opt.size.x() / opt.cell), extra);
      if (su <= 0) continue;
      const auto [sv, mv] = best_pair(strip_response(histogram(v, *v0, *v1), away),
                                      int(opt.size.y() / opt.cell), extra);
      if (sv <= 0) continue;
      Candidate c;
      c.score = su + sv;
      c.height = lo + (j + 1) * opt.tol;
      c.turn = t;
      c.cu = *u0 + (mu + 0.5) * opt.cell;
      c.cv = *v0 + (mv + 0.5) * opt.cell;
      if (best.size() == kKeep && c.score <= best.back().score) continue;
      best.push_back(c);
      std::sort(best.begin(), best.end(),
                [](const Candidate& x, const Candidate& y) { return x.score > y.score; });
      if (best.size() > kKeep) best.pop_back();
    }
  }
  return best;
}

}  // namespace

SizedRim find_sized_rim(const PlaneSamples& s, const std::vector<Eigen::Vector3d>& ups,
                        const SizedRimSearch& opt) {
  SizedRim out;
  out.why = "no rectangle of the given size at one height anywhere in view";
  if (!(opt.size.minCoeff() > 0) || s.points.size() < opt.min_slice) return out;
  for (const Eigen::Vector3d& up_in : ups) {
    const Eigen::Vector3d up = up_in.normalized();
    Eigen::Vector3d e1 = Eigen::Vector3d::UnitX() - up.x() * up;
    if (e1.norm() < 1e-6) e1 = Eigen::Vector3d::UnitY() - up.y() * up;
    e1.normalize();
    const Eigen::Vector3d e2 = up.cross(e1);
    Projected p;
    for (const Eigen::Vector3f& pf : s.points) {
      const Eigen::Vector3d q = pf.cast<double>();
      p.a.push_back(e1.dot(q)), p.b.push_back(e2.dot(q)), p.h.push_back(up.dot(q));
    }
    for (Candidate c : candidates_at(p, opt)) {
      refine(p, c, opt);
      const auto [cov, points] = coverage(p, c, opt);
      if (cov < opt.min_coverage || cov <= out.coverage) continue;
      const auto [level, above] = inside_shares(p, c, opt);
      if (level > 0.3 || above > opt.max_above || strip_contrast(p, c, opt) < opt.min_contrast)
        continue;
      out.found = true;
      out.why.clear();
      out.up = up;
      out.a1 = std::cos(c.turn) * e1 + std::sin(c.turn) * e2;
      out.a2 = up.cross(out.a1);
      out.centre = {c.cu, c.cv};
      out.height = c.height;
      out.coverage = cov;
      out.points = points;
    }
  }
  return out;
}

}  // namespace binpick
