// The bin's frame: the rim at each candidate "up" (the planes' normals, levelled from the rim's
// own samples, then the direction searched along the rim), judged by the rules of a frame, the
// best kept (docs/detect/bin.md, "Up", "The rim" and "Accepting a frame"). fit_bin (bin_fit.hpp)
// calls it, then places the sides out of view and finds the floor.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "host/detect/bin/bin_fit.hpp"
#include "host/detect/bin/bin_planes.hpp"
#include "host/detect/bin/bin_rim.hpp"

namespace binpick {

// A frame the rim gives at one up, and what holds it against later candidates.
struct FrameChoice {
  Eigen::Vector3d up, e1, e2;
  RimFit rim;
  bool on_floor = false;  // a level floor lies under the frame (floor_under)
  // Found only with one image side's samples above not counted, which asks for a level floor
  // under the frame too, though on_floor does not count it.
  bool forgiven = false;
};

// The frame: the rim at each candidate up (the planes', then the one searched along the rim),
// judged, the best kept. first_why: the largest plane's rim's reason, if it gave none;
// filled_why: the reason of the largest structure rejected.
struct FrameSearch {
  FrameChoice best;
  std::string first_why, filled_why;
};
FrameSearch choose_frame(const PlaneSamples& s, const std::vector<FoundPlane>& planes,
                         const BinFitOptions& opt, double tol);

// The candidate ups: the normals of the planes facing the camera within 60 degrees and spanning a
// quarter of the image both ways, most supported first (kUpCandidates of them), else the optical
// axis; from_planes: how many came from planes (at least 1).
std::vector<Eigen::Vector3d> plane_ups(const PlaneSamples& s, const std::vector<FoundPlane>& planes,
                                       std::size_t& from_planes);

// The frame's first axis, a1 = cos(angle) e1 + sin(angle) e2 (bin_rim.hpp).
Eigen::Vector3d frame_axis(const RimFit& rim, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2);

// Why a structure is no frame: the share of the points at its height that lie inside it.
std::string not_a_frame(double inside_share);

}  // namespace binpick
