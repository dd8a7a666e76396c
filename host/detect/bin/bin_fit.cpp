#include "host/detect/bin/bin_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "host/core/angles.hpp"
#include "host/core/quantile.hpp"
#include "host/detect/bin/bin_floor.hpp"
#include "host/detect/bin/bin_ground.hpp"
#include "host/detect/bin/bin_planes.hpp"
#include "host/detect/bin/bin_rim.hpp"
#include "host/detect/bin/bin_side.hpp"
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

// How far beyond `known` (along dir * axis) the points more than 3 tol below the rim reach: the
// 99.5th percentile of their distances beyond it (a stray point does not stretch the interior);
// 0 if there are too few.
// Planes tried as the floor's (see "up" in fit_bin), and rim fits per plane (each after the
// first with up from the previous one's rim).
constexpr std::size_t kUpCandidates = 3;
constexpr int kRimPasses = 3;
constexpr double kSearchedUpMargin = 1.5;

double farthest_below_rim(const PlaneSamples& s, const Eigen::Vector3d& up,
                          const Eigen::Vector3d& axis, double dir, double known, double rim_height,
                          double tol) {
  std::vector<double> beyond, heights;
  for (const Eigen::Vector3f& pf : s.points) {
    const Eigen::Vector3d p = pf.cast<double>();
    if (up.dot(p) > rim_height - 3 * tol) continue;
    const double b = dir * (axis.dot(p) - known);
    if (b > 0) beyond.push_back(b), heights.push_back(up.dot(p));
  }
  if (beyond.size() < 20) return 0.0;
  const double farthest = quantile(beyond, 0.995);
  // Through a wall one can see through (a wire-mesh basket) the farthest points are the ground
  // beyond it: where what lies past the last point in the upper 30 % below the rim (the top of a
  // wall, or parts heaped high) is the lowest level seen (90 % of it within 3 tol; the rest the
  // foot of the wall), the interior ends at that last high point
  // (docs/decisions/2026-11-25-bin-mesh-side-last-high-point.md).
  const double low = quantile(heights, 0.01), high_cut = rim_height - 0.3 * (rim_height - low);
  std::vector<double> high;
  for (std::size_t i = 0; i < beyond.size(); ++i)
    if (heights[i] > high_cut) high.push_back(beyond[i]);
  if (high.size() < 20) return farthest;
  const double last_high = quantile(high, 0.995);
  std::size_t past = 0, past_low = 0;
  for (std::size_t i = 0; i < beyond.size(); ++i) {
    if (beyond[i] <= last_high + 2 * tol) continue;
    ++past;
    past_low += heights[i] < low + 3 * tol;
  }
  return past >= 20 && double(past_low) >= 0.9 * double(past) ? last_high : farthest;
}

// How far a side of the frame lies beyond `from` (along dir * axis[k]) when the border band
// holds no rim there and no wall plane was found: the rim's strip or the wall among all samples
// (bin_side.hpp; with a level floor under the frame), else the farthest point seen below the
// rim (out of view, or no depth there: a shiny wall, a projector shadow), so that all the
// interior holds stays in and the rim sides seen stay out; unseen[dir > 0] says which it was.
double side_beyond(const PlaneSamples& s, const Eigen::Vector3d& up, const Eigen::Vector3d axis[2],
                   int k, double dir, double from, const RimFit& rim, bool on_floor, double tol,
                   bool unseen[2]) {
  unseen[dir > 0] = false;
  if (on_floor && rim.samples.size() >= 10) {
    std::vector<double> across;
    for (std::size_t i : rim.samples) across.push_back(axis[1 - k].dot(s.points[i].cast<double>()));
    SideSearch q;
    q.up = up, q.axis = axis[k], q.across = axis[1 - k], q.dir = dir, q.from = from;
    q.across_lo = quantile(across, 0.02), q.across_hi = quantile(across, 0.98);
    q.rim_height = rim.height, q.tol = tol;
    if (const std::optional<double> strip = rim_strip_beyond(s, q)) return *strip;
    if (const std::optional<double> wall = wall_beyond(s, q)) return *wall;
  }
  unseen[dir > 0] = true;
  return farthest_below_rim(s, up, axis[k], dir, from, rim.height, tol);
}

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

// The frame's first axis, a1 = cos(angle) e1 + sin(angle) e2 (bin_rim.hpp).
Eigen::Vector3d frame_axis(const RimFit& rim, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2) {
  return std::cos(rim.angle) * e1 + std::sin(rim.angle) * e2;
}

// The interior's edges with the sides not seen left open.
std::array<double, 4> open_edges(const RimFit& rim) {
  std::array<double, 4> open = rim.edge;
  for (int k = 0; k < 4; ++k)
    if (!rim.seen[std::size_t(k)]) open[std::size_t(k)] = k % 2 ? INFINITY : -INFINITY;
  return open;
}

std::string too_narrow(const Eigen::Vector2d& size, double min_side) {
  return fmt::format("the interior found is only {:.1f} x {:.1f} mm (a bin needs {:.1f} each way)",
                     size.x(), size.y(), min_side);
}

// The interior's width along each axis whose two sides were both seen (infinity where not).
Eigen::Vector2d seen_widths(const RimFit& rim) {
  Eigen::Vector2d w(INFINITY, INFINITY);
  for (int k = 0; k < 2; ++k)
    if (rim.seen[std::size_t(2 * k)] && rim.seen[std::size_t(2 * k + 1)])
      w[k] = rim.edge[std::size_t(2 * k + 1)] - rim.edge[std::size_t(2 * k)];
  return w;
}

std::string not_a_frame(double inside_share) {
  return fmt::format(
      "the structure at the highest height along the border is not a frame ({:.0f} % of the "
      "points at its height lie inside it)",
      100.0 * inside_share);
}

}  // namespace

double BinFit::floor_d() const { return -axes.col(2).dot(origin); }

double BinFit::tilt_degrees() const {
  return std::acos(std::clamp(-axes(2, 2), -1.0, 1.0)) / kDeg;
}

BinFit fit_bin(ocl::Device& dev, const std::vector<float>& xyzw, std::uint32_t width,
               std::uint32_t height, const BinFitOptions& opt) {
  if (opt.spec.mode == BinSpec::Mode::none) throw std::logic_error("fit_bin: no bin asked for");
  return fit_bin(dev, sample_points(xyzw, width, height), opt);
}

namespace {

// The fit; with the planes of the whole image given, along the border of s.window only.
BinFit fit_bin_in(ocl::Device& dev, const PlaneSamples& s, const BinFitOptions& opt,
                  const std::vector<FoundPlane>* found_planes) {
  BinFit bin;
  if (opt.spec.mode == BinSpec::Mode::none) throw std::logic_error("fit_bin: no bin asked for");
  bin.samples = s.points.size();
  bin.window = s.window;
  if (s.points.size() < 100) {
    bin.why = "too few points with depth";
    return bin;
  }
  std::vector<double> z;
  for (const auto& p : s.points) z.push_back(p.z());
  bin.tol = opt.tol > 0 ? opt.tol : std::max(2.0, 0.003 * quantile(z, 0.5));

  PlaneSearch ps;
  ps.tol = float(bin.tol);
  ps.seed = opt.seed;
  const std::vector<FoundPlane> planes = found_planes ? *found_planes : find_planes(dev, s, ps);
  bin.planes = planes.size();
  // A camera farther off than the bin is wide sees the ground all around it, and the rim lies
  // inside the border band, where fit_rim looks for it, or not in it at all (bin_ground.hpp):
  // the rim is then looked for along the border of the window of what stands above the ground.
  // Only there: along the image's border, the ground all around it, a heap of parts on the
  // ground with no bin gave a "frame" (BinFit.AHeapOnTheGroundIsNoBin;
  // docs/detect/bin.md, "The ground all around"; docs/decisions/2026-12-02-bin-ground-window.md).
  if (!found_planes) {
    GroundOptions go;
    go.tol = bin.tol;
    if (const std::optional<PixelWindow> w = window_above_ground(s, planes, go)) {
      PlaneSamples in_window = s;
      in_window.window = *w;
      return fit_bin_in(dev, in_window, opt, &planes);
    }
  }
  // "Up" is the normal of a large plane facing the camera that spans much of the image: the floor
  // with flat parts on it, or a layer of parts. With the camera tilted far (30 degrees) the near
  // wall's outer face is such a plane too, often the largest, and heights along its normal put
  // the rim and that face at one "height"; and in a bin full of bulky parts the floor is hidden
  // and the largest such plane is a layer of the pile, along which some "rim" is found too. So
  // each of the kUpCandidates largest is tried, and up is the one whose rim holds the most
  // samples: the true rim runs along the whole frame at one height only along the true up
  // (docs/detect/bin.md, "Up"; docs/decisions/2026-11-25-bin-up-best-rim-of-planes.md).
  std::vector<const FoundPlane*> candidates;
  for (const FoundPlane& p : planes)
    if (p.normal.z() <= -std::cos(60 * kDeg) && image_span(s, p) >= 0.25) candidates.push_back(&p);
  std::stable_sort(candidates.begin(), candidates.end(), [](const FoundPlane* a, const FoundPlane* b) {
    return a->inliers.size() > b->inliers.size();
  });
  if (candidates.size() > kUpCandidates) candidates.resize(kUpCandidates);
  std::vector<Eigen::Vector3d> ups;
  for (const FoundPlane* p : candidates) ups.push_back(p->normal);
  const std::size_t from_planes = std::max<std::size_t>(1, ups.size());
  if (ups.empty()) ups.push_back(Eigen::Vector3d(0, 0, -1));
  RimOptions ro;
  ro.tol = bin.tol;
  ro.focal = focal_estimate(s);
  Eigen::Vector3d up, e1, e2;
  RimFit rim;
  struct Choice {
    Eigen::Vector3d up, e1, e2;
    RimFit rim;
    bool on_floor = false;  // a level floor lies under the frame (floor_under)
    // Found only with one image side's samples above not counted, which asks for a level floor
    // under the frame too (below), though on_floor does not count it.
    bool forgiven = false;
  } best;
  std::size_t filled_points = 0;  // the largest structure rejected as no rim, and why
  std::string filled_why;
  const BorderBand band = border_band(s, ro.band);
  const double above_margin = std::max(2 * bin.tol, 4 * opt.noise);
  for (std::size_t c = 0;; ++c) {
    if (c == from_planes) {
      // Then the direction along which the rim holds the most samples (bin_up.hpp): in a bin
      // full of bulky parts seen tilted, none of the planes may be level. Not when a plane's up
      // gave a frame over a level floor already: the searched up could replace it only with half
      // as many rim samples again and a level floor of its own (below), which it never had, and
      // the search is a third of the fit's time
      // (docs/decisions/2026-12-01-bin-up-search-skipped-over-floor.md). Nor when a plane's up
      // gave a frame seen on all four sides (a full bin straight down: the floor hidden, the rim
      // whole): it replaced none of those; the frames it did replace were slices through heaps
      // (below; docs/decisions/2026-12-04-bin-up-search-skipped-full-frame.md).
      if (best.rim.found &&
          (best.on_floor || std::count(best.rim.seen.begin(), best.rim.seen.end(), true) == 4))
        break;
      RimUpSearch rs;
      rs.tol = bin.tol;
      const std::optional<RimUp> searched = search_rim_up(s, rs);
      if (!searched) break;
      ups.push_back(searched->up);
    }
    if (c == ups.size()) break;
    up = ups[c];
    // Then again with up from the rim's own plane (rim_normal), which is level where the first
    // plane may lean; also when no frame was found at the first up: a floor plane found on
    // leaning parts, a few degrees off, puts the far rim a few centimetres off the near one's
    // height, but the rim's samples at that height still give the level.
    for (int pass = 0; pass < kRimPasses; ++pass) {
      e1 = Eigen::Vector3d::UnitX() - up.x() * up;
      if (e1.norm() < 1e-6) e1 = Eigen::Vector3d::UnitY() - up.y() * up;
      e1.normalize();
      e2 = up.cross(e1);
      rim = fit_rim(s, up, e1, e2, ro);
      if (c == 0 && pass == 0 && !rim.found) bin.why = rim.why;  // the largest plane's reason
      // A frame found at a level up is the answer; a frame found at the first up is levelled
      // once (samples spread over 10 tolerances both ways); a structure that is no frame yet is
      // levelled from samples spread over 5 (one side and slivers of two others;
      // docs/decisions/2026-11-25-bin-near-rim-only.md).
      if (pass + 1 == kRimPasses || (rim.found && pass > 0)) break;
      const std::optional<Eigen::Vector3d> level =
          rim_normal(s, rim, up, bin.tol, rim.found ? 10.0 : 5.0);
      if (!level || std::acos(std::min(1.0, level->dot(up))) < 0.1 * kDeg) break;
      up = *level;
    }
    // A structure that fills its own frame is no rim (the far wall's inner face, a large plane
    // facing a camera tilted 30 degrees, is one "height" along its normal): checked here, with
    // the sides not seen left open, so that it does not outbid the real rim (after the choice
    // the check is made again with those sides placed).
    const Eigen::Vector3d b1 = frame_axis(rim, e1, e2), b2 = up.cross(b1);
    const std::array<double, 4> open = open_edges(rim);
    bool forgiven = false;  // found only with one image side's samples above not counted
    if (rim.found) {
      const double inside = share_inside(s, up, b1, b2, rim.height, open, bin.tol);
      std::size_t above = samples_above(band, up, rim.height + above_margin, false);
      if (double(above) > kMaxAboveRim * double(rim.points) &&
          std::count(rim.seen.begin(), rim.seen.end(), true) >= 2 &&
          floor_under(s, planes, up, b1, b2, open, rim.height, bin.tol, opt.noise).plane) {
        above = samples_above(band, up, rim.height + above_margin, true);
        forgiven = true;
      }
      // Checked here as well as at the end, so that the next candidate can win: two edges of
      // a robot arm's face beside the bin, with the ends of the rim's near side, made a narrow
      // "frame" along a wrong searched up (a wire-mesh basket, whose thin rim holds few
      // samples; docs/decisions/2026-11-25-bin-width-per-candidate.md).
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
      if (!rim.found && rim.points > filled_points) filled_points = rim.points, filled_why = rim.why;
    }
    // The searched up must hold half as many rim samples again as the planes' best: where
    // only the near side of the rim stands out, the turn about that side is free, and a
    // searched up turned some degrees about it gathers a few more samples off the wall's outer
    // face, while a wrong plane's rim holds several times fewer
    // (docs/decisions/2026-11-25-bin-searched-up-margin.md).
    const double need = c < from_planes ? 1.0 : kSearchedUpMargin;
    if (!rim.found || (best.rim.found && !(double(rim.points) > need * double(best.rim.points))))
      continue;
    // A frame seen on one side only cannot replace one seen on two or more: more samples at one
    // height along one side is weaker evidence of a frame than two sides meeting: a mesh wall's
    // horizontal bars, seen steeply, made a one-sided "frame" with more samples than the true
    // rim (docs/decisions/2026-12-02-bin-one-sided-frame-no-replace.md).
    const auto sides = [](const RimFit& r) {
      return std::count(r.seen.begin(), r.seen.end(), true);
    };
    if (best.rim.found && sides(rim) < 2 && sides(best.rim) >= 2) continue;
    // A frame with a level floor under it (the plane up came from, or one parallel, with nothing
    // below it) is a bin, not a slice of a pile: a later candidate (another plane's up, or the one
    // searched along the rim) must have one too to replace it. A thin rim holds few samples, and a
    // face at one "height" with a few of them (a robot arm's beside a wire-mesh basket) held more
    // (docs/decisions/2026-11-25-bin-frame-over-floor-holds.md). A frame found only with one
    // image side's samples above not counted has no such hold: a leaning layer of parts can be a
    // level floor under a small "frame", with the rim's high side above it one image side
    // (BinFit.UpFromTheRimWhenNoPlaneIsLevel).
    const bool on_floor =
        !forgiven &&
        floor_under(s, planes, up, b1, b2, open, rim.height, bin.tol, opt.noise).plane.has_value();
    if (best.on_floor && !on_floor) continue;
    // A frame with no level floor under it must be seen on two sides or more. Cut through a
    // heap of parts with no bin (the paper's scenes), the searched up made a slice of the heap
    // one "height" along the border, a "frame" seen on one side only, while no frame found in a
    // bin was (BinFit.ASliceThroughAHeapIsNoRim). Not three sides: a wire-mesh basket whose
    // floor the sensor barely sees, with an arm over one side and the far side out of view,
    // shows two (docs/decisions/2026-12-02-bin-one-side-needs-floor.md).
    // (A frame found with one image side not counted has a level floor under it, though
    // on_floor leaves it out.)
    if (!on_floor && !forgiven && std::count(rim.seen.begin(), rim.seen.end(), true) < 2) {
      if (rim.points > filled_points) {
        filled_points = rim.points;
        filled_why =
            "the structure at one height along the border is seen as one side of a frame only, "
            "with no level floor under it: a slice through a heap, not a rim";
      }
      continue;
    }
    best = {up, e1, e2, rim, on_floor, forgiven};
  }
  if (!best.rim.found) {
    if (bin.why.empty()) bin.why = filled_why;
    return bin;
  }
  up = best.up, e1 = best.e1, e2 = best.e2, rim = best.rim;
  bin.rim_points = rim.points;
  const Eigen::Vector3d a1 = frame_axis(rim, e1, e2);
  const Eigen::Vector3d a2 = up.cross(a1);
  const Eigen::Vector3d axis[2] = {a1, a2};
  std::array<double, 4> edge = rim.edge;
  // A level floor under the frame, for the side search (side_beyond): a forgiven frame was
  // forgiven only over one.
  const bool level_floor = best.on_floor || best.forgiven;
  // A side of the frame out of view (a tilted camera) or hidden: with a given size, the other
  // side's edge plus that size; else the nearest wall plane beyond the edge seen.
  const bool sized = opt.spec.mode == BinSpec::Mode::sized;
  for (int k = 0; k < 2; ++k) {
    const bool lo = rim.seen[2 * k], hi = rim.seen[2 * k + 1];
    if (lo && hi) continue;
    if (!lo && !hi) {
      // No side on this axis (only the near side of the rim stands out, bin_rim.cpp): the
      // interior runs to the farthest points seen below the rim both ways from the rim's
      // middle, so that all it holds stays in.
      if (sized) {
        bin.why = "two sides of the rim are out of view";
        return bin;
      }
      std::vector<double> along;
      for (std::size_t i : rim.samples) along.push_back(axis[k].dot(s.points[i].cast<double>()));
      const double middle = quantile(along, 0.5);
      bool unseen[2] = {false, false};
      const auto beyond = [&](double dir) {
        return side_beyond(s, up, axis, k, dir, middle, rim, level_floor, bin.tol, unseen);
      };
      const double to_lo = beyond(-1.0), to_hi = beyond(1.0);
      if (!(to_lo > 4 * bin.tol) || !(to_hi > 4 * bin.tol)) {
        bin.why = "only one side of the rim was found and no points below it on either hand";
        return bin;
      }
      edge[2 * k] = middle - to_lo;
      edge[2 * k + 1] = middle + to_hi;
      for (const char* sign : {"-", "+"})
        if (unseen[sign[0] == '+'])
          bin.unseen_sides.push_back(fmt::format("{}{}", sign, k == 0 ? "a1" : "a2"));
      continue;
    }
    const int known = lo ? 2 * k : 2 * k + 1, missing = lo ? 2 * k + 1 : 2 * k;
    const double dir = lo ? 1.0 : -1.0;  // from the edge seen toward the one missing
    if (sized) {
      const int other = 1 - k;
      if (!rim.seen[2 * other] || !rim.seen[2 * other + 1]) {
        bin.why = "two sides of the rim are out of view";
        return bin;
      }
      // The given size nearer the complete axis' is that axis'; this one gets the other.
      const double seen_other = edge[2 * other + 1] - edge[2 * other];
      const double w = opt.spec.size.x(), d = opt.spec.size.y();
      edge[missing] = edge[known] + dir * (std::abs(w - seen_other) < std::abs(d - seen_other) ? d : w);
      continue;
    }
    double nearest = INFINITY;
    for (const FoundPlane& p : planes) {
      if (std::abs(p.normal.dot(up)) > std::sin(10 * kDeg) ||
          std::abs(p.normal.dot(axis[k])) < std::cos(10 * kDeg))
        continue;
      std::vector<double> c;
      for (std::uint32_t i : p.inliers) c.push_back(axis[k].dot(s.points[i].cast<double>()));
      const double beyond = dir * (quantile(c, 0.5) - edge[known]);
      if (beyond > 4 * bin.tol && beyond < nearest) nearest = beyond;
    }
    if (!std::isfinite(nearest)) {
      // Neither rim in the border band nor wall seen on this side (side_beyond).
      bool missed[2] = {false, false};
      nearest = side_beyond(s, up, axis, k, dir, edge[known], rim, level_floor, bin.tol, missed);
      if (!(nearest > 4 * bin.tol)) {
        bin.why = "a side of the rim is out of view and neither a wall plane nor points below "
                  "the rim were found in its place";
        return bin;
      }
      if (missed[dir > 0])
        bin.unseen_sides.push_back(fmt::format("{}{}", dir > 0 ? '+' : '-', k == 0 ? "a1" : "a2"));
    }
    edge[missing] = edge[known] + dir * nearest;
  }
  const double inside_share = share_inside(s, up, a1, a2, rim.height, edge, bin.tol);
  if (inside_share > kMaxInsideShare) {
    bin.why = not_a_frame(inside_share);
    return bin;
  }
  const Eigen::Vector2d size(edge[1] - edge[0], edge[3] - edge[2]);
  if (!(size.minCoeff() >= opt.min_side)) {
    bin.why = too_narrow(size, opt.min_side);
    return bin;
  }
  const Eigen::Vector2d centre(0.5 * (edge[0] + edge[1]), 0.5 * (edge[2] + edge[3]));
  Eigen::Vector3d x = a1, y = a2;
  double long_side = size.x(), short_side = size.y();
  if (size.y() > size.x()) {
    x = a2, y = -a1;
    std::swap(long_side, short_side);
  }
  if (x.x() < 0) x = -x, y = -y;

  // The floor: below the rim, inside the rim's rectangle (bin_floor.hpp).
  double floor_h = 0;
  if (opt.spec.mode == BinSpec::Mode::sized) {
    floor_h = rim.height - opt.spec.size.z();
  } else {
    const FloorUnder f = floor_under(s, planes, up, a1, a2, edge, rim.height, bin.tol, opt.noise);
    const std::vector<double>& h = f.heights;
    bin.floor_plane = f.plane.has_value();
    if (f.plane) floor_h = *f.plane;
    if (!bin.floor_plane) {
      if (h.size() < 20) {
        bin.why = "no points inside the rim";
        return bin;
      }
      // The lowest points seen: the floor is no higher (0.1 %: a stray sample does not lower
      // it), less the noise (the 0.1st percentile of a noisy surface lies 3 sigma below it).
      floor_h = h[h.size() / 1000] + 3 * opt.noise;
    }
  }
  if (!(rim.height - floor_h > std::max(3 * bin.tol, opt.min_height))) {
    bin.why = fmt::format("the rim found is only {:.1f} mm over the floor (a bin needs {:.1f})",
                          rim.height - floor_h, std::max(3 * bin.tol, opt.min_height));
    return bin;
  }
  bin.found = true;
  bin.axes.col(0) = x;
  bin.axes.col(1) = y;
  bin.axes.col(2) = up;
  bin.origin = centre.x() * a1 + centre.y() * a2 + floor_h * up;
  for (const std::string& side : bin.unseen_sides) {
    const Eigen::Vector3d out = (side[0] == '+' ? 1.0 : -1.0) * (side[2] == '1' ? a1 : a2);
    const double ox = out.dot(x), oy = out.dot(y);
    bin.unseen_walls |= std::abs(ox) > std::abs(oy) ? (ox > 0 ? 1u : 2u) : (oy > 0 ? 4u : 8u);
  }
  bin.measured = {long_side, short_side, rim.height - floor_h};
  if (opt.spec.mode == BinSpec::Mode::sized)
    bin.interior = {std::max(opt.spec.size.x(), opt.spec.size.y()),
                    std::min(opt.spec.size.x(), opt.spec.size.y()), opt.spec.size.z()};
  else
    bin.interior = bin.measured;
  return bin;
}

}  // namespace

BinFit fit_bin(ocl::Device& dev, const PlaneSamples& s, const BinFitOptions& opt) {
  return fit_bin_in(dev, s, opt, nullptr);
}

RegionBox bin_interior_box(const BinFit& bin, double margin, double above,
                           double floor_clearance) {
  RegionBox b;
  b.R = bin.axes.transpose().cast<float>();
  b.t = bin.origin.cast<float>();
  b.lo = Eigen::Vector3d(-0.5 * bin.interior.x() + margin, -0.5 * bin.interior.y() + margin,
                         floor_clearance >= 0 ? floor_clearance : -margin).cast<float>();
  b.hi = Eigen::Vector3d(0.5 * bin.interior.x() - margin, 0.5 * bin.interior.y() - margin,
                         bin.interior.z() + above).cast<float>();
  return b;
}

BinWalls bin_walls(const BinFit& bin) {
  BinWalls w;
  // Moved out by the fit's tolerance and down from the rim by as much: a fitted wall a few mm
  // inside the true one would otherwise take the points seen just over a solid wall's top (a
  // ray over the rim crosses a plane further in lower down) for points seen through it
  // (docs/decisions/2026-12-02-bin-walls-moved-out.md).
  w.reach = (0.5 * bin.interior.head<2>() + Eigen::Vector2d::Constant(bin.tol)).cast<float>();
  w.height = float(bin.interior.z() - bin.tol);
  w.sides = 15u & ~bin.unseen_walls;  // a wall not seen is not where the interior ends
  return w;
}

RegionBox roi_box(const RoiSpec& roi, const BinFit* bin) {
  RegionBox b;
  if (roi.frame == RoiSpec::Frame::bin) {
    if (!bin || !bin->found) throw std::logic_error("roi_box: a bin-frame ROI without a bin");
    b.R = bin->axes.transpose().cast<float>();
    b.t = bin->origin.cast<float>();
  }
  b.lo = roi.lo.cast<float>();
  b.hi = roi.hi.cast<float>();
  return b;
}

std::string describe(const BinFit& bin) {
  if (!bin.found) return "bin: not found (" + bin.why + ")";
  const Eigen::Vector3d up = bin.axes.col(2);
  return fmt::format(
      "bin: interior {:.1f} x {:.1f} x {:.1f} mm (seen inside the rim: {:.1f} x {:.1f}), rim "
      "{:.1f} mm above the floor; floor {} up . p + {:.1f} = 0 with up ({:.4f}, {:.4f}, {:.4f}), "
      "tilted {:.1f} deg from the optical axis; floor centre ({:.1f}, {:.1f}, {:.1f}) mm; {} "
      "samples, {} planes, {} rim points, tolerance {:.1f} mm",
      bin.interior.x(), bin.interior.y(), bin.interior.z(), bin.measured.x(), bin.measured.y(),
      bin.interior.z(), bin.floor_plane ? "plane" : "(not seen as a plane)", bin.floor_d(),
      up.x(), up.y(), up.z(), bin.tilt_degrees(), bin.origin.x(), bin.origin.y(), bin.origin.z(),
      bin.samples, bin.planes, bin.rim_points, bin.tol) +
         (bin.window.u1 == 0
              ? std::string()
              : fmt::format("; the rim looked for along pixels {}-{} x {}-{}, the ground all "
                            "around",
                            bin.window.u0, bin.window.u1, bin.window.v0, bin.window.v1)) +
         (bin.unseen_sides.empty()
              ? std::string()
              : fmt::format("; {} side(s) of the rim unseen, the interior taken to the farthest "
                            "point below the rim there",
                            bin.unseen_sides.size()));
}

}  // namespace binpick
