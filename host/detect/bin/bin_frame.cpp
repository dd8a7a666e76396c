#include "host/detect/bin/bin_frame.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "host/core/angles.hpp"
#include "host/core/quantile.hpp"
#include "host/detect/bin/bin_floor.hpp"
#include "host/detect/bin/bin_up.hpp"

namespace binpick {
namespace {

// The fraction of the image a plane's inliers span (5th to 95th percentile), the smaller of
// the two directions: a floor or a rim spans much of the view, a part's face does not.
double image_span(const PlaneSamples& s, const FoundPlane& p) {
  std::vector<double> u, v;
  for (std::uint32_t i : p.inliers) u.push_back(s.u[i]), v.push_back(s.v[i]);
  return std::min((quantile(u, 0.95) - quantile(u, 0.05)) / s.width,
                  (quantile(v, 0.95) - quantile(v, 0.05)) / s.height);
}

// The focal length (pixels) seen in the samples: neighbours in a row differ by stride pixels and
// by stride / f in x / z. The median over the row pairs.
double focal_estimate(const PlaneSamples& s) {
  std::vector<double> f;
  for (std::size_t i = 0; i + 1 < s.points.size(); ++i) {
    if (s.v[i] != s.v[i + 1]) continue;
    const double a = s.points[i].x() / s.points[i].z(), b = s.points[i + 1].x() / s.points[i + 1].z();
    if (b - a > 1e-9) f.push_back(double(s.u[i + 1] - s.u[i]) / (b - a));
  }
  return f.empty() ? 1e9 : quantile(f, 0.5);
}

// Planes tried as the floor's (see "up" in fit_bin), and rim fits per plane (each after the
// first with up from the previous one's rim).
constexpr std::size_t kUpCandidates = 3;
constexpr int kRimPasses = 3;
constexpr double kSearchedUpMargin = 1.5;

// The rim is the highest structure along the image's border: of the border band's samples, at
// most this share of the rim's own count may stand above it (beyond 2 tol and 4 sigma of the
// image's noise). Cut through a heap of parts with no bin (the paper's scenes), a direction a
// few degrees off makes a slice of the heap one "height" along three sides; the heap's parts
// above the slice give it away (docs/decisions/2026-11-25-bin-nothing-above-rim.md).
// One image side may be covered by something above the rim, as the rim itself may be covered along
// one (bin_rim.hpp): a robot arm over the rim's side, out to the image's border. So where the
// frame has two sides or more seen and a level floor under it (floor_under), the samples above
// on the image side holding the most of them are not counted. A slice through a heap has no
// floor under it (the paper's scenes show none), and the heap's parts above it may lie mostly
// on one side, so both conditions are needed (BinFit.ASliceThroughAHeapIsNoRim;
// docs/decisions/2026-11-25-bin-covered-image-side.md).
constexpr double kMaxAboveRim = 0.1;


// The interior's edges with the sides not seen left open.
std::array<double, 4> open_edges(const RimFit& rim) {
  std::array<double, 4> open = rim.edge;
  for (int k = 0; k < 4; ++k)
    if (!rim.seen[std::size_t(k)]) open[std::size_t(k)] = k % 2 ? INFINITY : -INFINITY;
  return open;
}

// The interior's width along each axis whose two sides were both seen (infinity where not).
Eigen::Vector2d seen_widths(const RimFit& rim) {
  Eigen::Vector2d w(INFINITY, INFINITY);
  for (int k = 0; k < 2; ++k)
    if (rim.seen[std::size_t(2 * k)] && rim.seen[std::size_t(2 * k + 1)])
      w[k] = rim.edge[std::size_t(2 * k + 1)] - rim.edge[std::size_t(2 * k)];
  return w;
}




// The rim at `up`, then again with up from the rim's own plane (rim_normal), which is level where
// the first plane may lean; also when no frame was found at the first up: a floor plane found on
// leaning parts, a few degrees off, puts the far rim a few centimetres off the near one's height,
// but the rim's samples at that height still give the level. up, e1, e2: in and out. first_why:
// the first fit's reason, if it found no frame (null: not wanted).
RimFit levelled_rim(const PlaneSamples& s, Eigen::Vector3d& up, Eigen::Vector3d& e1,
                    Eigen::Vector3d& e2, const RimOptions& ro, double tol,
                    std::string* first_why) {
  RimFit rim;
  for (int pass = 0; pass < kRimPasses; ++pass) {
    e1 = Eigen::Vector3d::UnitX() - up.x() * up;
    if (e1.norm() < 1e-6) e1 = Eigen::Vector3d::UnitY() - up.y() * up;
    e1.normalize();
    e2 = up.cross(e1);
    rim = fit_rim(s, up, e1, e2, ro);
    if (first_why && pass == 0 && !rim.found) *first_why = rim.why;
    // A frame found at a level up is the answer; a frame found at the first up is levelled once
    // (samples spread over 10 tolerances both ways); a structure that is no frame yet is
    // levelled from samples spread over 5 (one side and slivers of two others;
    // docs/decisions/2026-11-25-bin-near-rim-only.md).
    if (pass + 1 == kRimPasses || (rim.found && pass > 0)) break;
    const std::optional<Eigen::Vector3d> level =
        rim_normal(s, rim, up, tol, rim.found ? 10.0 : 5.0);
    if (!level || std::acos(std::min(1.0, level->dot(up))) < 0.1 * kDeg) break;
    up = *level;
  }
  return rim;
}

// The rules a rim must pass at its own up, with the sides not seen left open (after the choice
// the frame is checked again with them placed): wide enough for a part, a frame and not a filled
// structure (the far wall's inner face, facing a camera tilted 30 degrees, is one "height" along
// its normal), nothing along the border above it. A rule that fails clears rim.found with its
// reason. Returns whether it passed only with one image side's samples above not counted
// (kMaxAboveRim says when that is allowed).
bool judge_rim(RimFit& rim, const PlaneSamples& s, const BorderBand& band,
               const std::vector<FoundPlane>& planes, const Eigen::Vector3d& up,
               const Eigen::Vector3d& b1, const Eigen::Vector3d& b2, double above_margin,
               double tol, const BinFitOptions& opt) {
  const std::array<double, 4> open = open_edges(rim);
  const double inside = share_inside(s, up, b1, b2, rim.height, open, tol);
  std::size_t above = samples_above(band, up, rim.height + above_margin, false);
  bool forgiven = false;
  if (double(above) > kMaxAboveRim * double(rim.points) &&
      std::count(rim.seen.begin(), rim.seen.end(), true) >= 2 &&
      floor_under(s, planes, up, b1, b2, open, rim.height, tol, opt.noise).plane) {
    above = samples_above(band, up, rim.height + above_margin, true);
    forgiven = true;
  }
  // Checked here as well as at the end, so that a narrow "frame" at a wrong up (edges of
  // something beside the bin) lets the next candidate win
  // (docs/decisions/2026-11-25-bin-width-per-candidate.md).
  if (!(seen_widths(rim).minCoeff() >= opt.min_side)) {
    rim.found = false;
    rim.why = fmt::format("the frame found is only {:.1f} mm across (a bin needs {:.1f})",
                          seen_widths(rim).minCoeff(), opt.min_side);
  } else if (inside > kMaxInsideShare) {
    rim.found = false;
    rim.why = not_a_frame(inside);
  } else if (double(above) > kMaxAboveRim * double(rim.points)) {
    rim.found = false;
    rim.why = fmt::format(
        "{} samples along the border stand above the structure at one height along three "
        "sides ({} samples): a slice through a heap, not a rim",
        above, rim.points);
  }
  return forgiven;
}

std::size_t sides_seen(const RimFit& r) {
  return std::size_t(std::count(r.seen.begin(), r.seen.end(), true));
}

// Whether a frame found at a later up beats the best so far on its rim: more samples than need
// times the best's (kSearchedUpMargin for the up searched along the rim: where only the near side
// stands out, a turn about it gathers a few more off the wall's outer face;
// docs/decisions/2026-11-25-bin-searched-up-margin.md), and not one side against two or more:
// two sides meeting are stronger evidence of a frame than more samples along one
// (docs/decisions/2026-12-02-bin-one-sided-frame-no-replace.md).
bool beats(const FrameChoice& best, const RimFit& rim, double need) {
  if (!best.rim.found) return true;
  if (!(double(rim.points) > need * double(best.rim.points))) return false;
  return !(sides_seen(rim) < 2 && sides_seen(best.rim) >= 2);
}

}  // namespace

// The ups tried first: the normals of the planes that face the camera within 60 degrees and span
// a quarter of the image both ways (the floor, the rim's plane, a layer of parts), most inliers
// first, at most kUpCandidates; the optical axis if none. from_planes: how many came from planes
// (at least 1). The true rim runs along the whole frame at one height only along the true up, so
// each is tried and the rim with the most samples wins (docs/detect/bin.md, "Up";
// docs/decisions/2026-11-25-bin-up-best-rim-of-planes.md).
std::vector<Eigen::Vector3d> plane_ups(const PlaneSamples& s, const std::vector<FoundPlane>& planes,
                                       std::size_t& from_planes) {
  std::vector<const FoundPlane*> candidates;
  for (const FoundPlane& p : planes)
    if (p.normal.z() <= -std::cos(60 * kDeg) && image_span(s, p) >= 0.25) candidates.push_back(&p);
  std::stable_sort(candidates.begin(), candidates.end(), [](const FoundPlane* a, const FoundPlane* b) {
    return a->inliers.size() > b->inliers.size();
  });
  if (candidates.size() > kUpCandidates) candidates.resize(kUpCandidates);
  std::vector<Eigen::Vector3d> ups;
  for (const FoundPlane* p : candidates) ups.push_back(p->normal);
  from_planes = std::max<std::size_t>(1, ups.size());
  if (ups.empty()) ups.push_back(Eigen::Vector3d(0, 0, -1));
  return ups;
}

// The frame's first axis, a1 = cos(angle) e1 + sin(angle) e2 (bin_rim.hpp).
Eigen::Vector3d frame_axis(const RimFit& rim, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2) {
  return std::cos(rim.angle) * e1 + std::sin(rim.angle) * e2;
}

std::string not_a_frame(double inside_share) {
  return fmt::format(
      "the structure at the highest height along the border is not a frame ({:.0f} % of the "
      "points at its height lie inside it)",
      100.0 * inside_share);
}

FrameSearch choose_frame(const PlaneSamples& s, const std::vector<FoundPlane>& planes,
                         const BinFitOptions& opt, double tol) {
  FrameSearch out;
  std::size_t from_planes = 0;
  std::vector<Eigen::Vector3d> ups = plane_ups(s, planes, from_planes);
  RimOptions ro;
  ro.tol = tol;
  ro.focal = focal_estimate(s);
  FrameChoice& best = out.best;
  std::size_t filled_points = 0;  // the largest structure rejected as no rim
  const BorderBand band = border_band(s, ro.band);
  const double above_margin = std::max(2 * tol, 4 * opt.noise);
  for (std::size_t c = 0;; ++c) {
    if (c == from_planes) {
      // Then the direction along which the rim holds the most samples (bin_up.hpp): in a bin full
      // of bulky parts seen tilted, none of the planes may be level. Not after a frame over a
      // level floor (docs/decisions/2026-12-01-bin-up-search-skipped-over-floor.md), nor after
      // one seen on all four sides (docs/decisions/2026-12-04-bin-up-search-skipped-full-frame.md).
      if (best.rim.found && (best.on_floor || sides_seen(best.rim) == 4)) break;
      RimUpSearch rs;
      rs.tol = tol;
      const std::optional<RimUp> searched = search_rim_up(s, rs);
      if (!searched) break;
      ups.push_back(searched->up);
    }
    if (c == ups.size()) break;
    Eigen::Vector3d up = ups[c], e1, e2;
    RimFit rim = levelled_rim(s, up, e1, e2, ro, tol, c == 0 ? &out.first_why : nullptr);
    const Eigen::Vector3d b1 = frame_axis(rim, e1, e2), b2 = up.cross(b1);
    bool forgiven = false;
    if (rim.found) {
      forgiven = judge_rim(rim, s, band, planes, up, b1, b2, above_margin, tol, opt);
      if (!rim.found && rim.points > filled_points)
        filled_points = rim.points, out.filled_why = rim.why;
    }
    if (!rim.found || !beats(best, rim, c < from_planes ? 1.0 : kSearchedUpMargin)) continue;
    // A frame over a level floor is a bin, not a slice of a pile: a later one must have a floor
    // too, however many samples it holds (a thin rim holds few;
    // docs/decisions/2026-11-25-bin-frame-over-floor-holds.md).
    const bool on_floor =
        !forgiven && floor_under(s, planes, up, b1, b2, open_edges(rim), rim.height, tol, opt.noise)
                         .plane.has_value();
    if (best.on_floor && !on_floor) continue;
    // A frame with no level floor under it must be seen on two sides or more: a slice through a
    // heap with no bin is seen on one (BinFit.ASliceThroughAHeapIsNoRim;
    // docs/decisions/2026-12-02-bin-one-side-needs-floor.md).
    if (!on_floor && !forgiven && sides_seen(rim) < 2) {
      if (rim.points > filled_points) {
        filled_points = rim.points;
        out.filled_why =
            "the structure at one height along the border is seen as one side of a frame only, "
            "with no level floor under it: a slice through a heap, not a rim";
      }
      continue;
    }
    best = {up, e1, e2, rim, on_floor, forgiven};
  }
  return out;
}

}  // namespace binpick
