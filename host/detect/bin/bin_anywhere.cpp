#include "host/detect/bin/bin_anywhere.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "host/core/angles.hpp"
#include "host/core/two_halves.hpp"
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
  double hw = 0, hd = 0;  // half the interior along u and v
  int slice = 0;          // the slice it came from (any size: evaluated on that slice's samples)
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

// A pair of strips: min of the two responses, the middle between them and their span (bins).
struct StripPair {
  double score = 0, middle = 0;
  int span = 0;
};

// Without a size: the best `keep` pairs among the response's 8 highest local peaks, spanning
// span_lo .. span_hi bins.
std::vector<StripPair> best_pairs(const std::vector<double>& f, int span_lo, int span_hi,
                                  std::size_t keep) {
  std::vector<int> peaks;
  const int n = int(f.size());
  for (int i = 0; i < n; ++i) {
    const double v = f[std::size_t(i)];
    bool top = v > 0;
    for (int d = -2; d <= 2 && top; ++d)
      if (d != 0 && i + d >= 0 && i + d < n)
        top = d < 0 ? v > f[std::size_t(i + d)] : v >= f[std::size_t(i + d)];
    if (top) peaks.push_back(i);
  }
  std::sort(peaks.begin(), peaks.end(),
            [&](int a, int b) { return f[std::size_t(a)] > f[std::size_t(b)]; });
  if (peaks.size() > 8) peaks.resize(8);
  std::vector<StripPair> pairs;
  for (std::size_t x = 0; x < peaks.size(); ++x)
    for (std::size_t y = 0; y < peaks.size(); ++y) {
      const int span = peaks[y] - peaks[x];
      if (span < span_lo || span > span_hi) continue;
      pairs.push_back({std::min(f[std::size_t(peaks[x])], f[std::size_t(peaks[y])]),
                       peaks[x] + 0.5 * span, span});
    }
  std::sort(pairs.begin(), pairs.end(),
            [](const StripPair& a, const StripPair& b) { return a.score > b.score; });
  if (pairs.size() > keep) pairs.resize(keep);
  return pairs;
}

// The turned coordinates of point i.
inline Eigen::Vector2d turned(const Projected& p, std::size_t i, double c, double s) {
  return {c * p.a[i] + s * p.b[i], -s * p.a[i] + c * p.b[i]};
}

// The strip's samples about a candidate (within tol of its height, in a band outside the inner
// edges), by side: 0 +u, 1 -u, 2 +v, 3 -v.
std::array<std::vector<std::size_t>, 4> strip_sides(const Projected& p, const Candidate& c,
                                                   const RimSearch& opt) {
  std::array<std::vector<std::size_t>, 4> sides;
  const double co = std::cos(c.turn), si = std::sin(c.turn);
  const double hw = c.hw, hd = c.hd, in = 2 * opt.tol, out = opt.strip + 2 * opt.tol;
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
void refine(const Projected& p, Candidate& c, const RimSearch& opt) {
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
    if (heights.size() >= 10) c.height = quantile(heights, 0.5);
    if (opt.size.minCoeff() > 0) {  // the size given: the centre midway between the strips
      if (has[0] && has[1]) c.cu = 0.5 * (median[0] + median[1]);
      if (has[2] && has[3]) c.cv = 0.5 * (median[2] + median[3]);
      continue;
    }
    // Any size: the inner edges, where each strip's points nearest the inside begin; away from
    // the corners, where the other sides' strips would pull them in.
    std::array<double, 4> edge{};
    for (int k = 0; k < 4; ++k) {
      std::vector<double> x;
      const double half = (k < 2 ? c.hd : c.hw) - 2 * opt.tol;
      for (std::size_t i : again[std::size_t(k)]) {
        const Eigen::Vector2d q = turned(p, i, co, si);
        const double along = k < 2 ? q.y() - c.cv : q.x() - c.cu;
        if (std::abs(along) < half) x.push_back(k < 2 ? q.x() : q.y());
      }
      has[std::size_t(k)] = x.size() >= 5;
      if (has[std::size_t(k)]) edge[std::size_t(k)] = quantile(x, k % 2 == 0 ? 0.05 : 0.95);
    }
    if (has[0] && has[1]) c.cu = 0.5 * (edge[0] + edge[1]), c.hw = 0.5 * (edge[0] - edge[1]);
    if (has[2] && has[3]) c.cv = 0.5 * (edge[2] + edge[3]), c.hd = 0.5 * (edge[2] - edge[3]);
  }
}

// The perimeter's segments (10 a side) the strip reaches: their share, the least share of one
// side, and the strip's samples.
struct Coverage {
  double share = 0, least_side = 0;
  std::size_t points = 0;
};
Coverage coverage(const Projected& p, const Candidate& c, const RimSearch& opt) {
  const auto sides = strip_sides(p, c, opt);
  const double co = std::cos(c.turn), si = std::sin(c.turn);
  constexpr int kSegments = 10;
  int reached = 0, least = kSegments;
  std::size_t points = 0;
  for (int k = 0; k < 4; ++k) {
    std::array<bool, kSegments> seg{};
    const double half = k < 2 ? c.hd : c.hw;
    for (std::size_t i : sides[std::size_t(k)]) {
      const Eigen::Vector2d q = turned(p, i, co, si) - Eigen::Vector2d(c.cu, c.cv);
      const double along = k < 2 ? q.y() : q.x();
      const int j = int(std::floor((along + half) / (2 * half) * kSegments));
      if (j >= 0 && j < kSegments) seg[std::size_t(j)] = true;
    }
    const int side = int(std::count(seg.begin(), seg.end(), true));
    reached += side;
    least = std::min(least, side);
    points += sides[std::size_t(k)].size();
  }
  return {double(reached) / (4 * kSegments), double(least) / kSegments, points};
}

// How much denser the strip is than the bands just inside and just outside it (kBand wide), at
// its height: a rim stands alone at its height, while a slice through the ground or a heap is as
// dense beside the "strip" as on it.
double strip_contrast(const Projected& p, const Candidate& c, const RimSearch& opt) {
  constexpr double kBand = 50;
  const double co = std::cos(c.turn), si = std::sin(c.turn);
  const double hw = c.hw, hd = c.hd, in = 2 * opt.tol, out = opt.strip + 2 * opt.tol;
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
                                        const RimSearch& opt) {
  const double co = std::cos(c.turn), si = std::sin(c.turn);
  std::size_t at = 0, above = 0, inside = 0, slice = 0;
  for (std::size_t i = 0; i < p.h.size(); ++i) {
    const Eigen::Vector2d q = turned(p, i, co, si) - Eigen::Vector2d(c.cu, c.cv);
    const bool in = std::abs(q.x()) < c.hw - 2 * opt.tol && std::abs(q.y()) < c.hd - 2 * opt.tol;
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

// What the rectangle holds: samples inside it (2 tol in) more than 3 tol above the lowest of
// them (1 %), and under its rim.
std::size_t held(const Projected& p, const Candidate& c, const RimSearch& opt) {
  const double co = std::cos(c.turn), si = std::sin(c.turn);
  std::vector<double> inside;
  for (std::size_t i = 0; i < p.h.size(); ++i) {
    const Eigen::Vector2d q = turned(p, i, co, si) - Eigen::Vector2d(c.cu, c.cv);
    if (std::abs(q.x()) < c.hw - 2 * opt.tol && std::abs(q.y()) < c.hd - 2 * opt.tol)
      inside.push_back(p.h[i]);
  }
  if (inside.size() < 20) return 0;
  const double low = quantile(inside, 0.01);
  return std::size_t(std::count_if(inside.begin(), inside.end(), [&](double h) {
    return h > low + 3 * opt.tol && h < c.height - opt.tol;
  }));
}

// The samples by height slice: slice j holds [lo + j tol, lo + (j + 2) tol).
std::vector<std::vector<std::size_t>> height_slices(const Projected& p, const RimSearch& opt,
                                                    double& lo) {
  lo = quantile(p.h, 0.001);
  const double hi = quantile(p.h, 0.999);
  const int slices = int(std::ceil((hi - lo) / opt.tol)) + 1;
  std::vector<std::vector<std::size_t>> in;
  if (slices <= 0 || slices > 100000) return in;
  in.resize(std::size_t(slices));
  for (std::size_t i = 0; i < p.h.size(); ++i) {
    const int k = int(std::floor((p.h[i] - lo) / opt.tol));
    if (k < 0 || k >= slices) continue;
    in[std::size_t(k)].push_back(i);
    if (k > 0) in[std::size_t(k - 1)].push_back(i);
  }
  return in;
}

// Keeps the `keep` best-scoring candidates in `list` (best first).
void offer(std::vector<Candidate>& list, const Candidate& c, std::size_t keep) {
  if (list.size() == keep && c.score <= list.back().score) return;
  list.insert(std::upper_bound(list.begin(), list.end(), c,
                               [](const Candidate& x, const Candidate& y) { return x.score > y.score; }),
              c);
  if (list.size() > keep) list.pop_back();
}

// The best candidates of slice j (samples idx, its middle `height`) over every turn: `keep` of
// them. u: scratch.
std::vector<Candidate> slice_candidates(const Projected& p, const std::vector<std::size_t>& idx,
                                        int j, double height, const RimSearch& opt,
                                        std::size_t keep, std::vector<double>& u) {
  std::vector<Candidate> list;
  const bool sized = opt.size.minCoeff() > 0;
  const int away = std::max(2, int(std::lround(2 * opt.tol / opt.cell)) + 2);
  const int extra = int(std::ceil(opt.strip / opt.cell));
  const double smallest = sized ? opt.size.y() : opt.min_side;
  const auto histogram = [&](const std::vector<double>& x, double x0, double x1) {
    std::vector<int> h(std::size_t((x1 - x0) / opt.cell) + 1, 0);
    for (double xi : x) ++h[std::size_t((xi - x0) / opt.cell)];
    return h;
  };
  // The strips across u at each turn; across v at turn t they are those across u at t + 90
  // degrees (at t - 90, mirrored), so each turn's histogram serves twice.
  const int turns = std::max(2, 2 * int(std::lround(90 / opt.turn_step_deg)));
  const int quarter = turns / 2;
  std::vector<std::vector<double>> response(static_cast<std::size_t>(turns));
  std::vector<double> lo(static_cast<std::size_t>(turns)), hi(static_cast<std::size_t>(turns));
  for (int k = 0; k < turns; ++k) {
    const double t = k * std::numbers::pi / turns, co = std::cos(t), si = std::sin(t);
    u.clear();
    for (std::size_t i : idx) u.push_back(co * p.a[i] + si * p.b[i]);
    const auto [u0, u1] = std::minmax_element(u.begin(), u.end());
    lo[std::size_t(k)] = *u0, hi[std::size_t(k)] = *u1;
    if (*u1 - *u0 >= smallest) response[std::size_t(k)] = strip_response(histogram(u, *u0, *u1), away);
  }
  for (int k = 0; k < turns; ++k) {
    const double t = k * std::numbers::pi / turns;
    const int m = k < quarter ? k + quarter : k - quarter;
    const std::vector<double>& fu = response[std::size_t(k)];
    if (fu.empty() || response[std::size_t(m)].empty()) continue;  // too small
    std::vector<double> fv = response[std::size_t(m)];
    const double u_start = lo[std::size_t(k)];
    double v_start = lo[std::size_t(m)];
    if (k >= quarter) {  // v = -u at t - 90: the bins reversed
      std::reverse(fv.begin(), fv.end());
      v_start = -lo[std::size_t(m)] - double(fv.size()) * opt.cell;
    }
    std::vector<StripPair> pu, pv;
    if (sized) {
      const auto [su, mu] = best_pair(fu, int(opt.size.x() / opt.cell), extra);
      const auto [sv, mv] = best_pair(fv, int(opt.size.y() / opt.cell), extra);
      if (su > 0 && sv > 0) pu = {{su, mu, 0}}, pv = {{sv, mv, 0}};
    } else {
      const int lo_span = int(opt.min_side / opt.cell), hi_span = int(opt.max_side / opt.cell) + extra;
      pu = best_pairs(fu, lo_span, hi_span, 3);
      pv = best_pairs(fv, lo_span, hi_span, 3);
    }
    for (const StripPair& a : pu)
      for (const StripPair& b : pv) {
        Candidate c;
        c.score = a.score + b.score;
        c.height = height;
        c.turn = t;
        c.cu = u_start + (a.middle + 0.5) * opt.cell;
        c.cv = v_start + (b.middle + 0.5) * opt.cell;
        // Sized: the inner edges at the size. Any: the strips' middles less a thin strip's
        // half, refined from the strips.
        c.hw = sized ? 0.5 * opt.size.x() : std::max(0.0, 0.5 * a.span * opt.cell - 10);
        c.hd = sized ? 0.5 * opt.size.y() : std::max(0.0, 0.5 * b.span * opt.cell - 10);
        c.slice = j;
        offer(list, c, keep);
      }
  }
  return list;
}

// The best candidates of one up, every slice with enough samples, every turn: of a given size
// the 8 best overall; of any size the 2 best of each slice, so that every height is searched
// whatever the density of the others (docs/decisions/2026-12-07-bin-anywhere.md). The slices on
// two threads (even ones here, odd ones on the other), merged in slice order: the same result
// as one thread's.
std::vector<Candidate> candidates_at(const Projected& p,
                                     const std::vector<std::vector<std::size_t>>& in, double lo,
                                     const RimSearch& opt) {
  const bool sized = opt.size.minCoeff() > 0;
  const std::size_t keep = sized ? 8 : 2, slices = in.size();
  std::vector<std::vector<Candidate>> of_slice(slices);
  const std::size_t evens = (slices + 1) / 2;
  in_two_halves(2 * evens, [&](std::size_t first, std::size_t last) {
    std::vector<double> u;
    for (std::size_t k = first; k < last; ++k) {
      const std::size_t j = k < evens ? 2 * k : 2 * (k - evens) + 1;
      if (j >= slices || in[j].size() < opt.min_slice) continue;
      of_slice[j] = slice_candidates(p, in[j], int(j), lo + double(j + 1) * opt.tol, opt, keep, u);
    }
  });
  std::vector<Candidate> all;
  for (const std::vector<Candidate>& list : of_slice)
    for (const Candidate& c : list) {
      if (sized) offer(all, c, keep);
      else all.push_back(c);
    }
  return all;
}

// The samples of each slice, as their own projection (candidates are refined and judged on their
// slice's samples, which the climb visits too).
std::vector<Projected> slice_projections(const Projected& p,
                                         const std::vector<std::vector<std::size_t>>& slices) {
  std::vector<Projected> out(slices.size());
  for (std::size_t j = 0; j < slices.size(); ++j)
    for (std::size_t i : slices[j])
      out[j].a.push_back(p.a[i]), out[j].b.push_back(p.b[i]), out[j].h.push_back(p.h[i]);
  return out;
}

// The judgement of a rim's strip at c's height, on the samples near it: it reaches the perimeter
// (without a size, every side: a rectangle stretched to clutter beside a bin, or three walls' tops
// over a ring closed lower down by something else, has a side empty) and stands out from the bands
// beside it.
bool strip_passes(const Projected& near, const Candidate& c, const RimSearch& opt,
                  Coverage& cover) {
  cover = coverage(near, c, opt);
  return cover.share >= opt.min_coverage &&
         (opt.size.minCoeff() > 0 || cover.least_side >= opt.min_side_coverage) &&
         strip_contrast(near, c, opt) >= opt.min_contrast;
}

// ... and of what lies inside, over every sample: no layer at the rim's height, little above it.
bool inside_passes(const Projected& p, const Candidate& c, const RimSearch& opt) {
  const auto [level, above] = inside_shares(p, c, opt);
  return level <= 0.3 && above <= opt.max_above;
}

// The rim is the highest ring of its rectangle: level slices through a wire basket's wall bars
// (or a solid wall) show the same ring lower down. The best rectangle is raised to the highest
// slice where it still passes.
void climb(const Projected& p, const std::vector<Projected>& slices, double lo, Candidate& c,
           const RimSearch& opt) {
  for (std::size_t j = slices.size(); j-- > 0;) {
    const double height = lo + double(j + 1) * opt.tol;
    if (height <= c.height + opt.tol) return;
    if (slices[j].h.size() < opt.min_slice / 4) continue;
    Candidate up = c;
    up.height = height;
    Coverage cover;
    if (!strip_passes(slices[j], up, opt, cover) || !inside_passes(p, up, opt)) continue;
    c.height = height;
    return;
  }
}

}  // namespace

AnywhereRim find_rim_anywhere(const PlaneSamples& s, const std::vector<Eigen::Vector3d>& ups,
                        const RimSearch& opt) {
  AnywhereRim out;
  const bool sized = opt.size.minCoeff() > 0;
  out.why = sized ? "no rectangle of the given size at one height anywhere in view"
                  : "no rim's rectangle at one height anywhere in view";
  if (s.points.size() < opt.min_slice || !(opt.min_side > 0 && opt.max_side >= opt.min_side))
    return out;
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
    double lo = 0;
    const std::vector<std::vector<std::size_t>> slices = height_slices(p, opt, lo);
    const std::vector<Projected> slice_points = slice_projections(p, slices);
    Candidate best;  // this up's, if it beat the ups before
    bool improved = false;
    for (Candidate c : candidates_at(p, slices, lo, opt)) {
      // Any size: refined and judged on its slice's samples first (many candidates), on all
      // of them only for what stands inside.
      const Projected& near = sized ? p : slice_points[std::size_t(c.slice)];
      refine(near, c, opt);
      if (!sized && !(2 * std::min(c.hw, c.hd) >= opt.min_side &&
                      2 * std::max(c.hw, c.hd) <= opt.max_side))
        continue;
      Coverage cover;
      if (!strip_passes(near, c, opt, cover)) continue;
      const double cov = cover.share;
      // Sized: the most perimeter. Any size: the most perimeter, but within 10 % of it the most
      // held (the bin with parts before an empty tray), then the highest (a slice through the
      // walls below the rim shows the same ring). These two look at every sample: last.
      const std::size_t holds = sized ? 0 : held(p, c, opt);
      if (out.found && (sized || std::abs(cov - out.coverage) > 0.1 ? cov <= out.coverage
                        : holds != out.held                        ? holds < out.held
                                                                   : c.height <= out.height))
        continue;
      if (!inside_passes(p, c, opt)) continue;
      best = c, improved = true;
      out.held = holds;
      out.size = {2 * c.hw, 2 * c.hd};
      out.found = true;
      out.why.clear();
      out.up = up;
      out.a1 = std::cos(c.turn) * e1 + std::sin(c.turn) * e2;
      out.a2 = up.cross(out.a1);
      out.centre = {c.cu, c.cv};
      out.height = c.height;
      out.coverage = cov;
      out.points = cover.points;
    }
    if (improved) {
      climb(p, slice_points, lo, best, opt);
      out.height = best.height;
    }
  }
  return out;
}

}  // namespace binpick
