// The ray spread of verification: does the posed model's surface lie where the sensor saw it,
// along the rays, as closely as the sensor's noise allows? (docs/detect/verify.md, "Ray spread")
//
// A depth sensor's noise is along its rays. A model point's ICP residual r (point-to-plane)
// divided by the cosine between its normal and the viewing ray is the distance from the model's
// tangent plane to the measured point along the ray: at a right pose, the sensor's noise
// whatever the slope of the surface. A pose laid on a similar but different object (a shaft on
// a bolt's shank or a tee's arm, of another radius) leaves a systematic error spread over the
// whole part: no region's mean is off, so the patch bias sees nothing, and the widened
// tolerance takes it as inliers, but the spread along the rays is wider than the noise.
//
// Per pose: the mean square of the along-ray residuals. The image's noise is the least of these
// over the poses with enough points (the best-fitting pose shows what the sensor does). The
// excess is the RMS beyond that noise, after two standard errors of the difference of the two
// estimates; past a dead band the score is multiplied by band / excess.
//
// Both estimates' uncertainty counts: with the pose's alone, right poses lost against a floor
// that lay low by chance. The mean square is not trimmed: a wrong pose's evidence is in its
// larger residuals (docs/decisions/2026-11-25-ray-spread.md).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include <Eigen/Core>

namespace binpick {

// One pose's along-ray residuals (mm): residuals[j] (NaN: none) / cos between the posed normal
// R n_j and the ray to R p_j + t (camera at the origin); points facing away give none.
std::vector<double> ray_residuals(std::span<const float> residuals, const Eigen::Matrix3d& R,
                                  const Eigen::Vector3d& t,
                                  std::span<const Eigen::Vector3f> points,
                                  std::span<const Eigen::Vector3f> normals);

struct RaySpread {
  double mean_square = 0;  // mm^2 (0 when n == 0)
  std::size_t n = 0;       // residuals it came from
};
RaySpread ray_spread(std::span<const double> e);

// The image's noise: the least mean square among the spreads of at least min_points residuals
// (the least of many small samples lies low by chance); n == 0 when none has that many.
RaySpread ray_floor(std::span<const RaySpread> poses, std::size_t min_points = 50);

// The RMS (mm) of a pose's along-ray residuals beyond the image's noise:
// sqrt(max(0, ms - floor (1 + 2 sqrt(2 / n + 2 / n_floor)))): for Gaussian noise a mean square
// of n values has a relative standard error sqrt(2 / n); both are estimates. 0 when either
// has no residuals.
double ray_excess(const RaySpread& pose, const RaySpread& floor);

// The score's factor for an excess past a dead band (both mm): 1 within it, band / excess past
// (look-alike holes, lookalike_holes.hpp, use it too).
inline double excess_factor(double excess, double band) {
  return excess > band ? band / excess : 1.0;
}

}  // namespace binpick
