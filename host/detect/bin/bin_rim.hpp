// The bin's rim for the bin fit (bin_fit.hpp): the top of the walls, a thin rectangular frame
// at one height, the highest structure along the image's border. Host code on a sparse sample
// (a few ten thousand points), given the "up" direction.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "host/detect/bin/bin_planes.hpp"

namespace binpick {

// The rim in the plane basis (e1, e2) orthogonal to up: heights are up . p (mm). The frame's axes
// are a1 = cos(angle) e1 + sin(angle) e2 and a2 = up x a1; edges are coordinates along them.
struct RimFit {
  bool found = false;
  std::string why;            // why not, when not found
  double height = 0;          // up . p of the rim's top
  std::size_t points = 0;     // samples on it
  std::vector<std::size_t> samples;  // their indices in the PlaneSamples
  double angle = 0;           // radians
  // The interior's inner edges {a1 low, a1 high, a2 low, a2 high}, and which were seen: a side
  // of the frame may be out of view (a tilted camera) or hidden.
  std::array<double, 4> edge{};
  std::array<bool, 4> seen{};
};

struct RimOptions {
  double band = 0.25;   // the border band: this fraction of the image on each side
  double tol = 5.0;     // height tolerance, mm (the plane search's)
  double focal = 0;     // pixels; with the samples' stride it gives their spacing on the rim
};

// The samples in the border band (fit_rim's), with the sides of the image each lies along.
struct BorderBand {
  std::vector<std::size_t> index;  // in the PlaneSamples
  std::vector<Eigen::Vector3f> points;
  std::vector<std::uint8_t> sides;  // bit 0 left, 1 right, 2 top, 3 bottom
};

// Every stride-th sample in the band (stride 1: all of them) along the border of the samples'
// window, with those outside the window (beyond its border: the ground around a bin) or without.
BorderBand border_band(const PlaneSamples& samples, double band, std::size_t stride = 1,
                       bool outside = true);

// How many of the band's samples stand above `height` along `up`; with one_side_may_be_covered,
// those on the image side that holds the most of them are not counted (a sample in a corner
// belongs to both its sides).
std::size_t samples_above(const BorderBand& band, const Eigen::Vector3d& up, double height,
                          bool one_side_may_be_covered);

// 1. Heights of the samples in the border band, histogram of tol-wide bins; the highest peak
//    (at least 3 % of the biggest and 1 % of the band) whose points lie along at least three
//    of the four sides of the image is the rim (a robot arm or a part at the border covers one).
// 2. Its points in the plane: the orientation whose histograms along both axes are sharpest
//    (sum of squared counts; 0.5-degree steps over 90 degrees) is the rectangle's.
// 3. Along each axis, the frame's two sides are the highest histogram bins below and above the
//    middle; a side is there when its peak holds at least 4 times the median count (the other
//    sides' points spread evenly). Each side runs inward over the bins holding at least 30 % of
//    its peak: a first, coarse edge. Then again with only the points off the other sides (which
//    run up to the edge): a side runs inward over the bins holding 5 % of its peak (one empty
//    bin allowed), and its inner edge is the innermost point of that run, moved in by half a
//    sample spacing. found needs a side on at least one axis; where the rim's points form one
//    band (only the near side of a bin seen from far off to one side), that band is a side.
RimFit fit_rim(const PlaneSamples& samples, const Eigen::Vector3d& up, const Eigen::Vector3d& e1,
               const Eigen::Vector3d& e2, const RimOptions& opt);

// The normal of the plane through the rim's samples (least squares), facing the camera, if it is
// a sound plane near `up` (also when the frame was not found: the structure at one height along
// the border then gives the level to try again with): at least 100 samples spread over a
// frame, not a line (the in-plane spread both ways over min_spread tol), RMS distance within
// tol, within 10 degrees of up. The rim is
// level by construction, while the plane "up" was first taken from (the floor with flat parts
// on it, or a layer of parts) may lean by a few degrees
// (docs/decisions/2026-11-24-bin-up-levelled-from-rim.md).
std::optional<Eigen::Vector3d> rim_normal(const PlaneSamples& samples, const RimFit& rim,
                                          const Eigen::Vector3d& up, double tol,
                                          double min_spread = 10.0);

// Whether p lies within the frame {a1 low, a1 high, a2 low, a2 high} (edges may be infinite).
inline bool in_frame(const Eigen::Vector3d& a1, const Eigen::Vector3d& a2,
                     const std::array<double, 4>& edge, const Eigen::Vector3d& p) {
  const double q1 = a1.dot(p), q2 = a2.dot(p);
  return q1 >= edge[0] && q1 <= edge[1] && q2 >= edge[2] && q2 <= edge[3];
}

// A frame, not a layer: of the samples at the rim's height, at most this share may lie inside
// the interior. A layer of parts at one height over the whole view is not a rim; a bin filled up
// to its rim is not found either (the whole image is then used, with a warning).
inline constexpr double kMaxInsideShare = 0.3;

// Of all the samples within 1.5 tol of the rim's height, the share inside the interior {a1 low,
// a1 high, a2 low, a2 high} by more than 2 tol: a frame leaves few there, a layer of parts most.
double share_inside(const PlaneSamples& samples, const Eigen::Vector3d& up,
                    const Eigen::Vector3d& a1, const Eigen::Vector3d& a2, double height,
                    const std::array<double, 4>& edge, double tol);

}  // namespace binpick
