#include "host/detect/bin/bin_side.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

namespace binpick {
namespace {

constexpr std::size_t kMinSideSamples = 20;
constexpr int kCells = 10;            // the frame's width (and the wall's height) in cells ...
constexpr int kMinAcross = 6;         // ... of which a side covers most of the width
constexpr int kMinHeights = 4;        // ... and a wall a good part of the heights
constexpr double kStandOut = 3.0;     // times the median window's count
constexpr double kInnerQuantile = 0.1;  // of the window's samples: the side's inner edge

struct Sample {
  double beyond;  // dir * (axis . p - from), mm
  int across;     // cell across the frame
  int height;     // cell of height (walls only; 0 for the rim)
};

// The nearest window of the samples (two bins of the rim fit's width) that holds at least
// kMinSideSamples, kStandOut times the median window, kMinAcross cells across and min_heights
// cells of height: its inner edge's distance.
std::optional<double> nearest_side(const std::vector<Sample>& at, double tol, int min_heights) {
  if (at.size() < kMinSideSamples) return std::nullopt;
  const double width = std::max(tol, 4.0);
  double farthest = 0;
  for (const Sample& x : at) farthest = std::max(farthest, x.beyond);
  const std::size_t bins = std::size_t(farthest / width) + 2;
  std::vector<std::uint32_t> count(bins, 0), across(bins, 0), heights(bins, 0);  // cell bit sets
  for (const Sample& x : at) {
    const std::size_t b = std::size_t(x.beyond / width);
    ++count[b];
    across[b] |= 1u << x.across;
    heights[b] |= 1u << x.height;
  }
  // The median window, empty ones included: about 0 beyond a side that stands alone, the count
  // of every window over a level sheet of parts.
  std::vector<std::uint32_t> windows;
  for (std::size_t b = 0; b + 1 < bins; ++b) windows.push_back(count[b] + count[b + 1]);
  std::nth_element(windows.begin(), windows.begin() + std::ptrdiff_t(windows.size() / 2),
                   windows.end());
  const double background = windows[windows.size() / 2];
  for (std::size_t b = 0; b + 1 < bins; ++b) {
    const std::uint32_t n = count[b] + count[b + 1];
    if (n < kMinSideSamples || double(n) < kStandOut * background) continue;
    if (std::popcount(across[b] | across[b + 1]) < kMinAcross ||
        std::popcount(heights[b] | heights[b + 1]) < min_heights)
      continue;
    // Its inner edge: a low quantile of its samples, not the lowest, so that parts lying
    // against the side, whose samples share the window, do not pull it in.
    std::vector<double> in;
    for (const Sample& x : at) {
      const std::size_t xb = std::size_t(x.beyond / width);
      if (xb == b || xb == b + 1) in.push_back(x.beyond);
    }
    const auto k = in.begin() + std::ptrdiff_t(kInnerQuantile * double(in.size() - 1));
    std::nth_element(in.begin(), k, in.end());
    return *k;
  }
  return std::nullopt;
}

bool usable(const SideSearch& q) { return q.across_hi - q.across_lo > 0 && q.tol > 0; }

// The sample's place beyond the edge and across, if it lies beyond (4 tolerances) and across
// within the frame.
std::optional<Sample> place(const SideSearch& q, const Eigen::Vector3d& p) {
  const double beyond = q.dir * (q.axis.dot(p) - q.from);
  const double a = (q.across.dot(p) - q.across_lo) / (q.across_hi - q.across_lo);
  if (!(beyond > 4 * q.tol) || !(a >= 0 && a < 1)) return std::nullopt;
  return Sample{beyond, int(a * kCells), 0};
}

}  // namespace

std::optional<double> rim_strip_beyond(const PlaneSamples& s, const SideSearch& q) {
  if (!usable(q)) return std::nullopt;
  std::vector<Sample> at;
  for (const Eigen::Vector3f& pf : s.points) {
    const Eigen::Vector3d p = pf.cast<double>();
    if (!(std::abs(q.up.dot(p) - q.rim_height) <= 1.5 * q.tol)) continue;
    if (const std::optional<Sample> x = place(q, p)) at.push_back(*x);
  }
  return nearest_side(at, q.tol, 1);
}

std::optional<double> wall_beyond(const PlaneSamples& s, const SideSearch& q) {
  if (!usable(q)) return std::nullopt;
  const double top = q.rim_height - 3 * q.tol;
  double low = INFINITY;
  for (const Eigen::Vector3f& pf : s.points) low = std::min(low, q.up.dot(pf.cast<double>()));
  if (!(top - low > 4 * q.tol)) return std::nullopt;
  std::vector<Sample> at;
  for (const Eigen::Vector3f& pf : s.points) {
    const Eigen::Vector3d p = pf.cast<double>();
    const double h = q.up.dot(p);
    if (!(h < top)) continue;
    if (std::optional<Sample> x = place(q, p)) {
      x->height = std::min(kCells - 1, int((h - low) / (top - low) * kCells));
      at.push_back(*x);
    }
  }
  return nearest_side(at, q.tol, kMinHeights);
}

}  // namespace binpick
