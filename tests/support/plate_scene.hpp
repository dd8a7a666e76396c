// A depth image of the built-in plate lying on a plane one sheet thickness beneath it (a plate
// on a plate), for the probe tests of verification (tests/detect/verify/test_lookalike_holes.cpp,
// test_edge_step.cpp).
#pragma once

#include <Eigen/Geometry>

#include "host/detect/scene/depth_to_points.hpp"
#include "host/detect/refine/pose_fit.hpp"
#include "host/train/ppf_model.hpp"

namespace binpick::test {

// The camera: 320 x 240, f = 500 px, so that at 500 mm a pixel is a millimetre.
bp_camera plate_camera();

// The plate face up about 500 mm ahead, a little tilted.
Eigen::Isometry3d plate_pose();

// The plate's surface at `pose` over the plane 1.5 mm beneath it along its normal (the plate
// beneath's top face), 0.5 mm Gaussian noise (seeded). holes_without_depth: no depth wherever
// the plate is not (a structured-light sensor whose projector cannot light the bottom of a
// hole).
PointImage plate_over_plane(const bp_camera& cam, const Eigen::Isometry3d& pose,
                            bool holes_without_depth);

// The image with no depth in every other square of patch x patch pixels (a checkerboard): a
// sensor that loses depth in patches, on the part and around it alike (shiny sheet metal).
PointImage without_depth_in_patches(PointImage image, std::uint32_t patch);

// The plate at `pose` over a floor floor_z from the camera (a plane facing it), 0.3 mm Gaussian
// noise (seeded): for a plate seen steeply, where the plane beneath it would run past the camera.
PointImage plate_over_floor(const bp_camera& cam, const Eigen::Isometry3d& pose, float floor_z);

// The plane of the plate's face towards the camera at `pose`, without the plate: a plate pose
// laid on a larger flat face (another part's, a robot arm's). 0.5 mm Gaussian noise (seeded); no
// depth where the plane lies behind the camera or beyond 3 m.
PointImage plane_of_plate_face(const bp_camera& cam, const Eigen::Isometry3d& pose);

// The fit geometry the probe tests verify with: the model's diameter, voxel and centroid.
FitGeometry plate_fit_geometry(const PpfModel& model);

}  // namespace binpick::test
