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
#include "host/detect/bin/bin_anywhere.hpp"
#include "host/detect/bin/bin_floor.hpp"
#include "host/detect/bin/bin_frame.hpp"
#include "host/detect/bin/bin_ground.hpp"
#include "host/detect/bin/bin_planes.hpp"
#include "host/detect/bin/bin_rim.hpp"
#include "host/detect/bin/bin_side.hpp"
#include "host/detect/bin/bin_up.hpp"

namespace binpick {
namespace {


// How far beyond `known` (along dir * axis) the points more than 3 tol below the rim reach: the
// 99.5th percentile of their distances beyond it (a stray point does not stretch the interior);
// 0 if there are too few.

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




// The plane and height tolerance: given, or 0.3 % of the median depth and at least 2 mm.
double fit_tolerance(const PlaneSamples& s, double given) {
  if (given > 0) return given;
  std::vector<double> z;
  for (const auto& p : s.points) z.push_back(p.z());
  return std::max(2.0, 0.003 * (z.empty() ? 0.0 : quantile(z, 0.5)));
}

std::string too_narrow(const Eigen::Vector2d& size, double min_side) {
  return fmt::format("the interior found is only {:.1f} x {:.1f} mm (a bin needs {:.1f} each way)",
                     size.x(), size.y(), min_side);
}



}  // namespace

double BinFit::floor_d() const { return -axes.col(2).dot(origin); }

double BinFit::tilt_degrees() const {
  return std::acos(std::clamp(-axes(2, 2), -1.0, 1.0)) / kDeg;
}

BinFit fit_bin(ocl::Device& dev, const std::vector<float>& xyzw, std::uint32_t width,
               std::uint32_t height, const BinFitOptions& opt) {
  return fit_bin(dev, sample_points(xyzw, width, height), opt);
}

namespace {


// The interior's edges along the frame's axes with each side not seen placed: with a given size,
// the other side's edge plus that size; else the nearest wall plane beyond the edge seen, or the
// farthest points below the rim (side_beyond). "" or the reason there is no bin.
std::string place_unseen_sides(const PlaneSamples& s, const std::vector<FoundPlane>& planes,
                               const BinFitOptions& opt, const FrameChoice& f,
                               const Eigen::Vector3d axis[2], double tol,
                               std::array<double, 4>& edge, std::vector<std::string>& unseen) {
  const RimFit& rim = f.rim;
  const Eigen::Vector3d& up = f.up;
  // A level floor under the frame, for the side search: a forgiven frame was forgiven only over
  // one.
  const bool level_floor = f.on_floor || f.forgiven;
  const bool sized = opt.spec.mode == BinSpec::Mode::sized;
  for (int k = 0; k < 2; ++k) {
    const bool lo = rim.seen[2 * k], hi = rim.seen[2 * k + 1];
    if (lo && hi) continue;
    if (!lo && !hi) {
      // No side on this axis (only the near side of the rim stands out, bin_rim.cpp): the
      // interior runs to the farthest points seen below the rim both ways from the rim's middle,
      // so that all it holds stays in.
      if (sized) return "two sides of the rim are out of view";
      std::vector<double> along;
      for (std::size_t i : rim.samples) along.push_back(axis[k].dot(s.points[i].cast<double>()));
      const double middle = quantile(along, 0.5);
      bool missed[2] = {false, false};
      const auto beyond = [&](double dir) {
        return side_beyond(s, up, axis, k, dir, middle, rim, level_floor, tol, missed);
      };
      const double to_lo = beyond(-1.0), to_hi = beyond(1.0);
      if (!(to_lo > 4 * tol) || !(to_hi > 4 * tol))
        return "only one side of the rim was found and no points below it on either hand";
      edge[2 * k] = middle - to_lo;
      edge[2 * k + 1] = middle + to_hi;
      for (const char* sign : {"-", "+"})
        if (missed[sign[0] == '+'])
          unseen.push_back(fmt::format("{}{}", sign, k == 0 ? "a1" : "a2"));
      continue;
    }
    const int known = lo ? 2 * k : 2 * k + 1, missing = lo ? 2 * k + 1 : 2 * k;
    const double dir = lo ? 1.0 : -1.0;  // from the edge seen toward the one missing
    if (sized) {
      const int other = 1 - k;
      if (!rim.seen[2 * other] || !rim.seen[2 * other + 1])
        return "two sides of the rim are out of view";
      // The given size nearer the complete axis' is that axis'; this one gets the other.
      const double seen_other = edge[2 * other + 1] - edge[2 * other];
      const double w = opt.spec.size.x(), d = opt.spec.size.y();
      edge[missing] =
          edge[known] + dir * (std::abs(w - seen_other) < std::abs(d - seen_other) ? d : w);
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
      if (beyond > 4 * tol && beyond < nearest) nearest = beyond;
    }
    if (!std::isfinite(nearest)) {
      // Neither rim in the border band nor wall seen on this side (side_beyond).
      bool missed[2] = {false, false};
      nearest = side_beyond(s, up, axis, k, dir, edge[known], rim, level_floor, tol, missed);
      if (!(nearest > 4 * tol))
        return "a side of the rim is out of view and neither a wall plane nor points below the "
               "rim were found in its place";
      if (missed[dir > 0])
        unseen.push_back(fmt::format("{}{}", dir > 0 ? '+' : '-', k == 0 ? "a1" : "a2"));
    }
    edge[missing] = edge[known] + dir * nearest;
  }
  return {};
}

// The floor's height along up below the rim, inside its rectangle (bin_floor.hpp): a level plane,
// else the lowest points seen (0.1 %: a stray sample does not lower it) less the noise (the 0.1st
// percentile of a noisy surface lies 3 sigma below it); with a given size, the rim less its depth.
// None, with bin.why, when too few points lie inside. Sets bin.floor_plane.
std::optional<double> floor_height(const PlaneSamples& s, const std::vector<FoundPlane>& planes,
                                   const BinFitOptions& opt, const FrameChoice& f,
                                   const Eigen::Vector3d& a1, const Eigen::Vector3d& a2,
                                   const std::array<double, 4>& edge, double tol, BinFit& bin) {
  if (opt.spec.mode == BinSpec::Mode::sized) return f.rim.height - opt.spec.size.z();
  const FloorUnder under = floor_under(s, planes, f.up, a1, a2, edge, f.rim.height, tol, opt.noise);
  bin.floor_plane = under.plane.has_value();
  if (under.plane) return *under.plane;
  const std::vector<double>& h = under.heights;
  if (h.size() < 20) {
    bin.why = "no points inside the rim";
    return std::nullopt;
  }
  return h[h.size() / 1000] + 3 * opt.noise;
}

// The fit along the border, on the image's planes; in_window: along the border of s.window only
// (already chosen). In order: the tolerance; the window above the ground, where the ground shows
// all around; the frame (choose_frame); its sides out of view placed; the whole frame checked
// again; the floor.
BinFit fit_bin_in(const PlaneSamples& s, const BinFitOptions& opt,
                  const std::vector<FoundPlane>& planes, bool in_window) {
  BinFit bin;
  bin.samples = s.points.size();
  bin.window = s.window;
  if (s.points.size() < 100) {
    bin.why = "too few points with depth";
    return bin;
  }
  bin.tol = fit_tolerance(s, opt.tol);
  bin.planes = planes.size();
  // A camera farther off than the bin is wide sees the ground all around it: the rim is then
  // looked for along the border of the window of what stands above the ground (bin_ground.hpp;
  // docs/detect/bin.md, "The ground all around").
  if (!in_window) {
    GroundOptions go;
    go.tol = bin.tol;
    if (const std::optional<PixelWindow> w = window_above_ground(s, planes, go)) {
      PlaneSamples windowed = s;
      windowed.window = *w;
      return fit_bin_in(windowed, opt, planes, true);
    }
  }
  const FrameSearch search = choose_frame(s, planes, opt, bin.tol);
  bin.why = search.first_why;
  const FrameChoice& frame = search.best;
  if (!frame.rim.found) {
    if (bin.why.empty()) bin.why = search.filled_why;
    return bin;
  }
  const RimFit& rim = frame.rim;
  const Eigen::Vector3d& up = frame.up;
  bin.rim_points = rim.points;
  const Eigen::Vector3d a1 = frame_axis(rim, frame.e1, frame.e2);
  const Eigen::Vector3d a2 = up.cross(a1);
  const Eigen::Vector3d axis[2] = {a1, a2};
  std::array<double, 4> edge = rim.edge;
  std::string why = place_unseen_sides(s, planes, opt, frame, axis, bin.tol, edge, bin.unseen_sides);
  if (!why.empty()) {
    bin.why = std::move(why);
    return bin;
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
  const std::optional<double> floor =
      floor_height(s, planes, opt, frame, a1, a2, edge, bin.tol, bin);
  if (!floor) return bin;
  const double floor_h = *floor;
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

// Whether a frame found along the border is the bin of the given size: each side seen inside its
// rim within 10 % of the size given (a side out of view was placed at the size, so agrees).
bool matches_size(const BinFit& bin, const Eigen::Vector3d& size) {
  const double w = std::max(size.x(), size.y()), d = std::min(size.x(), size.y());
  return std::abs(bin.measured.x() - w) <= 0.1 * w && std::abs(bin.measured.y() - d) <= 0.1 * d;
}

// Whether the bin holds something: of the samples inside it (2 tol in from the walls), at least
// 20 and 2 % lie more than 3 tol above its floor and under its rim.
bool holds_something(const BinFit& bin, const PlaneSamples& s) {
  std::size_t inside = 0, held = 0;
  const double t = bin.tol;
  for (const Eigen::Vector3f& pf : s.points) {
    const Eigen::Vector3d q = bin.axes.transpose() * (pf.cast<double>() - bin.origin);
    if (std::abs(q.x()) > 0.5 * bin.interior.x() - 2 * t ||
        std::abs(q.y()) > 0.5 * bin.interior.y() - 2 * t || q.z() > bin.interior.z() - t)
      continue;
    ++inside;
    held += q.z() > 3 * t;
  }
  return held >= 20 && double(held) >= 0.02 * double(inside);
}

// A bin anywhere in view (bin_anywhere.hpp), at the planes' candidate ups: of the size given,
// its floor the rim less H; of any size, its floor the level plane under it or its lowest points,
// as fit_bin_in's.
BinFit fit_anywhere(const PlaneSamples& s, const BinFitOptions& opt,
                    const std::vector<FoundPlane>& planes) {
  BinFit bin;
  bin.samples = s.points.size();
  bin.tol = fit_tolerance(s, opt.tol);
  bin.planes = planes.size();
  std::size_t from_planes = 0;
  RimSearch search;
  const bool sized = opt.spec.mode == BinSpec::Mode::sized;
  const Eigen::Vector3d& size = opt.spec.size;
  if (sized) search.size = {std::max(size.x(), size.y()), std::min(size.x(), size.y())};
  // Without a size, a frame anywhere is a weaker clue than one along the border (edges of parts
  // at one height can make rectangles too): it must be able to hold a pile, two parts wide and,
  // below, a part and a half deep, and 100 mm both ways (docs/decisions/2026-12-07-bin-anywhere.md).
  search.min_side = sized ? std::max(opt.min_side, 100.0) : std::max(2 * opt.min_side, 100.0);
  const double min_depth = std::max({3 * search.tol, 3 * opt.min_height, 100.0});
  search.tol = bin.tol;
  const AnywhereRim rim = find_rim_anywhere(s, plane_ups(s, planes, from_planes), search);
  if (!rim.found) {
    bin.why = rim.why;
    return bin;
  }
  // x along the longer side, pointing to the camera's right.
  Eigen::Vector3d x = rim.a1, y = rim.a2;
  Eigen::Vector2d wd = rim.size;
  if (wd.y() > wd.x()) x = rim.a2, y = -rim.a1, std::swap(wd.x(), wd.y());
  if (x.x() < 0) x = -x, y = -y;
  double floor_h = sized ? rim.height - size.z() : 0.0;
  if (!sized) {
    const std::array<double, 4> edge = {rim.centre.x() - 0.5 * rim.size.x(),
                                        rim.centre.x() + 0.5 * rim.size.x(),
                                        rim.centre.y() - 0.5 * rim.size.y(),
                                        rim.centre.y() + 0.5 * rim.size.y()};
    const FloorUnder under =
        floor_under(s, planes, rim.up, rim.a1, rim.a2, edge, rim.height, bin.tol, opt.noise);
    bin.floor_plane = under.plane.has_value();
    if (!under.plane && under.heights.size() < 20) {
      bin.why = "no points inside the rim found anywhere in view";
      return bin;
    }
    floor_h = under.plane ? *under.plane
                          : under.heights[under.heights.size() / 1000] + 3 * opt.noise;
    if (!(rim.height - floor_h > min_depth)) {
      bin.why = fmt::format("the rim found anywhere in view is only {:.1f} mm over its floor (a bin "
                            "found there needs {:.1f})",
                            rim.height - floor_h, min_depth);
      return bin;
    }
  }
  bin.found = bin.anywhere = true;
  bin.axes.col(0) = x;
  bin.axes.col(1) = y;
  bin.axes.col(2) = rim.up;
  bin.origin = rim.centre.x() * rim.a1 + rim.centre.y() * rim.a2 + floor_h * rim.up;
  bin.interior = bin.measured = {wd.x(), wd.y(), rim.height - floor_h};
  bin.rim_points = rim.points;
  bin.coverage = rim.coverage;
  return bin;
}

}  // namespace

BinFit fit_bin(ocl::Device& dev, const PlaneSamples& s, const BinFitOptions& opt) {
  if (opt.spec.mode == BinSpec::Mode::none) throw std::logic_error("fit_bin: no bin asked for");
  if (opt.spec.mode == BinSpec::Mode::given) return given_bin(opt.spec, s, opt.tol);
  if (s.points.size() < 100) return fit_bin_in(s, opt, {}, false);  // says: too few points
  // The image's planes, found once for the fit along the border and the search anywhere.
  PlaneSearch ps;
  ps.tol = float(fit_tolerance(s, opt.tol));
  ps.seed = opt.seed;
  const std::vector<FoundPlane> planes = find_planes(dev, s, ps);
  BinFit bin = fit_bin_in(s, opt, planes, false);
  // A frame along the border stands when it is of the size given, or (any size) when the rim
  // was seen on every side (a side placed at the farthest point below the rim may reach over
  // clutter), and when it holds something (the bin to pick from holds parts); else the search
  // anywhere decides (docs/decisions/2026-12-07-bin-anywhere.md).
  const bool sized = opt.spec.mode == BinSpec::Mode::sized;
  if (bin.found && (sized ? matches_size(bin, opt.spec.size) : bin.unseen_sides.empty()) &&
      holds_something(bin, s))
    return bin;
  // The rim along the border is no bin (of this size): look for its rectangle anywhere.
  const BinFit anywhere = fit_anywhere(s, opt, planes);
  if (anywhere.found) return anywhere;
  if (!bin.found) bin.why += "; " + anywhere.why;
  return bin;
}

BinFit given_bin(const BinSpec& spec, const PlaneSamples& s, double tol) {
  if (spec.mode != BinSpec::Mode::given) throw std::logic_error("given_bin: no bin given");
  BinFit bin;
  bin.found = bin.given = bin.floor_plane = true;
  bin.axes = spec.R;
  bin.origin = spec.t;
  bin.interior = bin.measured = spec.size;
  bin.samples = s.points.size();
  bin.tol = fit_tolerance(s, tol);
  return bin;
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
  if (bin.given) {
    const Eigen::Vector3d up = bin.axes.col(2);
    return fmt::format(
        "bin: given (--bin-pose), interior {:.1f} x {:.1f} x {:.1f} mm, floor centre ({:.1f}, "
        "{:.1f}, {:.1f}) mm, up ({:.4f}, {:.4f}, {:.4f}), tilted {:.1f} deg from the optical "
        "axis; tolerance {:.1f} mm",
        bin.interior.x(), bin.interior.y(), bin.interior.z(), bin.origin.x(), bin.origin.y(),
        bin.origin.z(), up.x(), up.y(), up.z(), bin.tilt_degrees(), bin.tol);
  }
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
         (bin.anywhere ? fmt::format("; the rim's rectangle found anywhere in view ({:.0f} % of "
                                     "its perimeter seen)",
                                     100 * bin.coverage)
                       : std::string()) +
         (bin.unseen_sides.empty()
              ? std::string()
              : fmt::format("; {} side(s) of the rim unseen, the interior taken to the farthest "
                            "point below the rim there",
                            bin.unseen_sides.size()));
}

}  // namespace binpick
