// The collision test of pick planning (docs/picks.md): for each candidate (a gripper at
// one grasp of one detection, in the camera frame) the measured points of its pixel window inside
// the gripper, and how close the others on its side of the grasp come (kernels/pick_shared.h).
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "host/core/gripper.hpp"
#include "host/runtime/cl/cl_buffer.hpp"
#include "kernels/binpick_shared.h"
#include "kernels/pick_shared.h"

namespace binpick {

// The candidate of a gripper's solids at grasp_in_camera (the grasp's frame, grasp.hpp, in the
// camera frame), its window the pixels that can show a point within cap of the solids.
bp_pick_candidate pick_candidate(const std::vector<GripperSolid>& solids,
                                 const Eigen::Isometry3d& grasp_in_camera, const bp_camera& cam,
                                 float tolerance, float cap);

// Routine: the pick_clearance kernel on dev over a point image (4 floats a pixel, w = 1 where
// there is a point) of cam's size.
std::vector<bp_pick_result> pick_clearance(ocl::Device& dev, const ocl::Buffer<float>& points,
                                           const bp_camera& cam,
                                           const std::vector<bp_pick_candidate>& candidates);
// Reference: the same in plain C++.
std::vector<bp_pick_result> pick_clearance_reference(const std::vector<float>& points,
                                                     const bp_camera& cam,
                                                     const std::vector<bp_pick_candidate>& candidates);

}  // namespace binpick
