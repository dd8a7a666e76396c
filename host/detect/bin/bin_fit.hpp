// Finding the bin in a depth image (--bin auto, --bin W,D,H), so that detection can leave the
// bin out: its rim and walls are often the highest things in view.
//
// The bin frame: origin at the centre of the interior's floor, z up (the floor's normal, toward
// the camera), x along the interior's longer side (W), y = z x x along the shorter (D); x points
// to the camera's right (x . camera x >= 0). The interior is
// [-W/2, W/2] x [-D/2, D/2] x [0, H], H the rim's height above the floor.
//
// How (docs/detect/bin.md, "Finding the bin"): a sparse sample of the points; dominant planes by
// RANSAC scored on the device (bin_planes.hpp); "up" = the normal of the best-supported plane that
// faces the camera (within 60 degrees of the optical axis) and spans at least a quarter of the
// image both ways (the floor, or the rim's plane), else the optical axis; the rim = the highest
// structure at one height along the image border, and the interior = the rectangle inside its frame
// (bin_rim.hpp; a side out of view ends at the nearest wall plane beyond the side seen, or at the
// given size, or, with neither rim nor wall seen there, at the farthest point seen below the rim);
// the floor = the plane parallel to up with the most points inside that rectangle, below the rim
// (else the lowest points inside it). With a given size, the rim and its rectangle's centre and
// orientation are found the same way and the floor is the rim minus H. Where the border gives no
// bin (of the size given; without one, with every side seen) the rim's rectangle is searched
// anywhere in view (bin_anywhere.hpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "host/detect/bin/bin_planes.hpp"
#include "host/detect/params/bin_spec.hpp"
#include "host/detect/bin/scene_mask.hpp"
#include "host/runtime/cl/cl_buffer.hpp"

namespace binpick {

struct BinFitOptions {
  BinSpec spec;               // find or sized (none: nothing is fitted)
  double tol = 0;             // plane and height tolerance (mm); 0: max(2, 0.3 % of the median depth)
  std::uint32_t seed = 1;     // RANSAC's draws: same image, same bin
  double min_height = 0;      // a rim lower than this over the floor is no bin (mm)
  double min_side = 0;        // an interior narrower than this is no bin (mm)
  // The image's depth noise, sigma in mm (depth_noise.hpp): samples under a level plane by
  // more than 4 sigma (and 3 tol) say it is a layer of parts, not the floor.
  double noise = 0;
};

struct BinFit {
  bool found = false;
  std::string why;                                      // when not found
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();   // columns: bin x, y, z in the camera frame
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();     // floor centre, camera frame (mm)
  Eigen::Vector3d interior = Eigen::Vector3d::Zero();   // W, D, H (mm)
  Eigen::Vector3d measured = Eigen::Vector3d::Zero();   // W, D seen inside the rim; H (sized: as given)
  bool floor_plane = false;  // the floor is a fitted plane (else rim - H or the lowest points)
  bool given = false;        // placed from a --bin-pose file, not fitted
  // The rim's rectangle found anywhere in view (bin_anywhere.hpp), where the rim along the border
  // was no bin; coverage: the share of its perimeter the rim's samples reach.
  bool anywhere = false;
  double coverage = 0;
  // Sides of the rim where neither the rim nor a wall plane was seen ("+a1" ...): the interior
  // there ends at the farthest point seen below the rim, so W or D may be short of the truth.
  std::vector<std::string> unseen_sides;
  // The same in the bin's frame: bit 0 the side at +x (axes.col(0)), 1 at -x, 2 at +y, 3 at -y.
  std::uint32_t unseen_walls = 0;
  std::size_t samples = 0, planes = 0, rim_points = 0;
  // The window along whose border the rim was found: what stands above the ground all around
  // the bin (bin_ground.hpp), or the whole image (u1 = 0).
  PixelWindow window;
  double tol = 0;
  // The floor plane in the camera frame: up . p + floor_d = 0 (up = axes.col(2)).
  double floor_d() const;
  // Angle between up and the camera's viewing direction reversed (0: looking straight down).
  double tilt_degrees() const;
};

// Routine: on a point image (xyzw a pixel, w = 0 without data) held on the host; the planes are
// scored on dev. Never throws for a scene without a bin: found = false and why. A spec of
// Mode::given is placed as given, with the tolerance of the image's fit (given_bin).
BinFit fit_bin(ocl::Device& dev, const std::vector<float>& xyzw, std::uint32_t width,
               std::uint32_t height, const BinFitOptions& opt);
// The same on the samples of the point image (sample_points; from the device's point image
// without reading all of it back): the same fit.
BinFit fit_bin(ocl::Device& dev, const PlaneSamples& samples, const BinFitOptions& opt);

// The bin a spec of Mode::given places (a fixed cell's, bin_pose_file.hpp): found, its floor a
// plane, the tolerance (tol, or as fit_bin takes it from the samples' median depth) that of a
// fit in this image.
BinFit given_bin(const BinSpec& spec, const PlaneSamples& samples, double tol = 0);

// The interior shrunk by margin (mm) on the sides, up to `above` over the rim (parts may pile
// higher). From floor_clearance (mm) above the floor when it is >= 0: the floor itself is no
// part, and where much of it shows, its points outvote a part in the crops; else from margin
// below the floor (the floor stays).
RegionBox bin_interior_box(const BinFit& bin, double margin, double above,
                           double floor_clearance = -1);

// The interior's walls for the see-through test of the mask (scene_mask.hpp), a fit tolerance
// outside the interior and under the rim; those of the sides the fit did not see left out.
BinWalls bin_walls(const BinFit& bin);

// The ROI's box; a bin-frame ROI needs a found bin (std::logic_error otherwise).
RegionBox roi_box(const RoiSpec& roi, const BinFit* bin);

// One line for --verbose: what was found, or why not.
std::string describe(const BinFit& bin);

}  // namespace binpick
