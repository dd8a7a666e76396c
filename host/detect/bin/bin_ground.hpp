// The ground around a bin, for the bin fit (bin_fit.hpp). A camera farther from the bin than
// the bin is wide sees the floor the bin stands on all around it: the image's border is then
// that ground, and the rim, which fit_rim looks for in the border band (bin_rim.hpp), lies
// inside the band or not in it at all. Along the border of the window of what stands above the
// ground, the rim is at the border again.
#pragma once

#include <optional>
#include <vector>

#include "host/detect/bin/bin_planes.hpp"

namespace binpick {

struct GroundOptions {
  double ring = 0.05;        // the image's outer ring: this fraction of it on each side
  double ring_share = 0.5;   // the ground holds at least this share of each side's ring samples
  double max_below = 0.02;   // at most this share of the samples lies below the ground
  double max_area = 0.8;     // the window is at most this share of the image, or no window
  double margin = 0.02;      // the window grows by this fraction of the image each way
  double tol = 5.0;          // mm: within 2 tol of the plane is on the ground
  // The window's ends where what stands above the ground is narrower across than this share
  // of its typical width (a robot arm reaching out of the bin) are left out, unless less than
  // min_kept of the window would be left.
  double narrow_share = 0.5;
  double min_kept = 0.3;
};

// The window of the samples standing more than 3 tol above the ground (their 0.5-99.5 % range
// of pixels, an end at the image's border left out where they are narrow there, grown by the
// margin), if one of the planes is a ground: the lowest level (at most
// max_below of the samples under it by 2 tol), holding ring_share of the ring's samples on
// every side of the image with depth in its ring (10 samples), and there are three such sides
// or more, with the window small enough. Every side, not three of four: a robot arm reaching
// from over the rim to beside the camera, or a heap on the ground, made "frames" along the
// window's border (docs/decisions/2026-12-02-bin-ground-window.md). A side without depth there
// (a tilted camera looking past the ground's end) says nothing.
std::optional<PixelWindow> window_above_ground(const PlaneSamples& samples,
                                               const std::vector<FoundPlane>& planes,
                                               const GroundOptions& opt);

}  // namespace binpick
