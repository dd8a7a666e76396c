// The rival cap of verification (docs/detect/verify.md, "Rival cap"; figures:
// docs/decisions/2026-11-25-rival.md): two poses that lie on the same measured points are two
// answers to one question, and the points can say which fits better.
//
// A part turned end for end (a stepped shaft whose ends differ by a millimetre of radius) lies
// on the same points as the right pose. Every other factor asks a pose alone whether it fits
// within the noise, and at 3 % noise (1.8 mm on the shaft) both do: the wrong pose's extra
// millimetre lies inside the widened tolerance, and its spread along the rays is inside two
// standard errors of the image's noise. Compared with each other on the same measured points,
// the noise cancels: per point, the difference of the two poses' squared along-ray residuals
// has the mean delta^2 (the wrong pose's systematic error) and a spread of about 2 sigma delta,
// so a few hundred points tell the two apart where neither alone is told from the noise.
//
// Per pair of poses (A, B): the union of the measured points each one's ICP used; at each, each
// pose's along-ray residual to the tangent plane of its model point at that pixel (projective,
// as ICP pairs them), squared and clipped at the tolerance. The pair are rivals if both have
// model surface at `min_shared` of the union's points at least. A point where one of them has
// none is left unexplained by it and costs it the clip (`count_unexplained`): a pose that turns
// a protruding feature out of view shows fewer points, all agreeing, and would otherwise
// outscore the right pose. If B's mean exceeds A's by more than `significance` standard errors
// of the paired differences (and the dead bands), B is out-fitted: its score becomes at most
// A's score times ms_A / ms_B.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "host/detect/verify/verified_pose.hpp"
#include "kernels/binpick_shared.h"

namespace binpick {

// The measured points behind one pose's residuals: a residual r = nq . (p - q) (pose_fit_shared.h)
// of the posed model point q (normal nq) and the measured point p on the ray of q's pixel gives
// p's depth. residuals: one per model point, NaN where it gave no ICP term.
std::vector<Eigen::Vector3f> measured_points(std::span<const float> residuals,
                                             const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                                             std::span<const Eigen::Vector3f> points,
                                             std::span<const Eigen::Vector3f> normals,
                                             const bp_camera& cam);

// A pose's model surface as the camera sees it: at each pixel of the posed model's window, the
// model point facing the camera that projects nearest to it (within a few pixels: the points'
// spacing), the nearer one on a tie.
class PosedSurface {
 public:
  PosedSurface(const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
               std::span<const Eigen::Vector3f> points, std::span<const Eigen::Vector3f> normals,
               const bp_camera& cam, float spacing);
  // The along-ray residual (mm) of the measured point m (camera frame): its distance along the
  // ray from the tangent plane of the model point at its pixel. NaN: no model point there.
  double along_ray(const Eigen::Vector3f& m) const;

 private:
  static constexpr int kMaxRadius = 8;  // pixels
  // The index of the model point standing for pixel (u, v), -1 if none.
  std::int32_t nearest(int u, int v) const;
  bp_camera cam_;
  float band_ = 0;                              // mm: nearer by this hides
  int radius_ = 1;                              // pixels: a point's disc, and a cell's side
  int u0_ = 0, v0_ = 0, cells_u_ = 0, cells_v_ = 0;  // the window's corner and its cells
  std::vector<std::uint32_t> cell_start_;       // per cell, its first entry in cell_points_
  std::vector<std::uint32_t> cell_points_;      // point indices, by cell, in index order
  std::vector<Eigen::Vector3f> q_, nq_;         // posed points and normals
  std::vector<Eigen::Vector2f> pixel_;          // their image positions
};

struct RivalComparison {
  std::size_t union_size = 0, shared = 0;  // measured points, and those both have surface at
  std::size_t compared = 0;                // those the means are over
  double ms_a = 0, ms_b = 0;               // mean clipped squared residual, mm^2
  double standard_error = 0;               // of the mean of (B's - A's), mm^2
  bool stopped = false;  // given up: the poses could no longer share min_shared of the union
};
// A's and B's residuals on the union of their measured points.
RivalComparison compare_rivals(const PosedSurface& a, std::span<const Eigen::Vector3f> measured_a,
                               const PosedSurface& b, std::span<const Eigen::Vector3f> measured_b,
                               double tolerance, bool count_unexplained);
// The same, given each pose's residuals at its own measured points (own_residuals), which a
// pose compared with many rivals needs only once. With min_shared > 0 it gives up as soon as
// fewer than that share of the union could have surface of both poses (most pairs near each
// other are not rivals: a plate beside another): then `stopped`, union_size is the whole
// union's, shared those found so far (so still below the share) and nothing is compared.
std::vector<double> own_residuals(const PosedSurface& surface,
                                  std::span<const Eigen::Vector3f> measured);
RivalComparison compare_rivals(const PosedSurface& a, std::span<const Eigen::Vector3f> measured_a,
                               std::span<const double> own_a, const PosedSurface& b,
                               std::span<const Eigen::Vector3f> measured_b,
                               std::span<const double> own_b, double tolerance,
                               bool count_unexplained, double min_shared = 0);

// Poses whose posed centroids lie farther apart than this fraction of the diameter are not
// compared (they cannot share most of their points); a pruning for speed.
inline constexpr double kRivalCentreRatio = 0.5;
// The dead band's floor as an RMS, fraction of the diameter (RivalOptions::dead_band_floor).
inline constexpr double kRivalFloorRatio = 0.005;

struct RivalOptions {
  double significance = 2;      // standard errors; 0: off
  double min_shared = 0.8;      // share of the union's points both poses have surface at
  // The worse mean square must exceed the better by this share of it (at noise, clipping and
  // occlusion boundaries differ a few per cent between right poses) ...
  double dead_band = 0.05;
  // ... and by this square (mm^2): without noise, what is left is the model's sampling, which
  // differs from pose to pose (0: none).
  double dead_band_floor = 0;
  std::size_t min_points = 30;  // fewer shared points: no comparison
  double max_centre_distance = 0;  // mm; poses whose centroids lie farther apart are not compared
  // A measured point of one pose where the other has no model surface costs the other the
  // clip (it leaves the point unexplained); false: only the shared points are compared.
  bool count_unexplained = true;
};

// Sets the rival cap of every pose out-fitted by a rival (the scores before any cap count) and
// records the comparison (PoseEvidence::rival_shared, own_ms, rival_ms). Each pose's measured
// points: VerifiedPose::measured; points, normals: the model's (fit points), spacing: theirs
// (mm); centroid: the model's.
void cap_by_rivals(std::vector<VerifiedPose>& poses, std::span<const Eigen::Vector3f> points,
                   std::span<const Eigen::Vector3f> normals, float spacing, const bp_camera& cam,
                   const Eigen::Vector3d& centroid, const RivalOptions& opt);

}  // namespace binpick
