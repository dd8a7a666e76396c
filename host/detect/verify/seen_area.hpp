// The seen area of verification: how much of the part a pose shows the sensor
// (docs/detect/verify.md, "Seen area").
//
// The score is a share: the model points that agree among those the pose shows the camera. A
// plate seen nearly edge on, or a part of which a corner peeks out of the pile, shows few
// points, each seen by fewer pixels the more obliquely it faces the camera, and a few points
// agree by chance on any surface: plate poses laid steeply on a robot arm's side face
// outscored right plates lying face up. So each pose's *seen area* is measured: its visible
// model points weighted by the cosine between the normal and the ray (a point's share of the
// pixels, projected area), missing depth counting half as in the score; over the part's *mean
// area*, the same sum over all model points facing a camera averaged over every viewing
// direction (the mean projected area of the part's sampled surface: a quarter of a closed
// surface's points). The score is multiplied by min(1, share / scale): a pose that shows the
// sensor less than `scale` times what the part shows from an average direction loses in
// proportion; one that shows more keeps its score. A plate face up shows about twice its mean
// area, edge on at 75 degrees about half of it. Off by default (--verify-area 0): it prefers
// poses seen face on, which is no evidence about the pose
// (docs/decisions/2026-11-28-seen-area-off.md).
#pragma once

#include <cstdint>
#include <span>

#include <Eigen/Core>

namespace binpick {

// Viewing directions the mean area averages over (a Fibonacci sphere).
inline constexpr int kAreaDirections = 128;

// The mean over kAreaDirections viewing directions d of sum_i max(0, -n_i . d): the points'
// projected area, in points, from an average direction. normals: unit.
double mean_projected_area(std::span<const Eigen::Vector3f> normals);

// The seen area of a pose (R, t; model to camera, mm): over the model points whose class
// (pose_fit_shared.h) is not hidden, the cosine between the posed normal and the ray to the
// camera, halved where the class is missing. One class, point and normal per model point.
double seen_area(std::span<const std::uint8_t> classes, const Eigen::Matrix3d& R,
                 const Eigen::Vector3d& t, std::span<const Eigen::Vector3f> points,
                 std::span<const Eigen::Vector3f> normals);

// min(1, share / scale); 1 for scale <= 0 (off), 0 for share <= 0.
double area_factor(double share, double scale);

}  // namespace binpick
