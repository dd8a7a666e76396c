// Pick planning (docs/picks.md): for the detections scoring --pick-score or more, each
// grasp of the gripper's kind at the detected pose, kept if its approach lies within the cone
// about the bin's down, the gripper stays inside the bin's walls and above its floor, and no
// measured point lies inside the gripper; each detection's clearest grasp is its pick, and the
// picks are ordered by score, clearance and height.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "host/core/grasp.hpp"
#include "host/core/gripper.hpp"
#include "host/detect/bin/bin_fit.hpp"
#include "host/detect/params/detect_params.hpp"
#include "host/detect/select/detection.hpp"
#include "host/runtime/cl/cl_buffer.hpp"
#include "kernels/binpick_shared.h"

namespace binpick {

struct PickOptions {
  // The parameters' own defaults (declared once, in DetectParams).
  double min_score = DetectParams{}.pick_score;  // --pick-score: a detection scoring less is not picked
  double approach_cone = DetectParams{}.approach_cone;  // degrees about the bin's down (or the view axis)
  double tolerance = 1;         // mm: a point deeper than this inside the gripper collides
  // mm: how far the gripper may reach past the bin's walls and floor (the bin is one fitted or
  // given model, not noisy pixels: the depth noise does not widen it).
  double bin_tolerance = 1;
  double part_diameter = 0;     // mm: the clearance that counts fully is a quarter of it
  std::size_t max_colliding = 3;  // points inside the gripper tolerated (single stray pixels)
};

// Each detection's pick or the reason it has none, in the order of `detections`.
// Routine: the collision test on dev (pick_clearance.hpp) over the point image of cam; bin: the
// bin found, if any.
std::vector<PlannedPick> plan_picks(ocl::Device& dev, const ocl::Buffer<float>& points,
                                    const bp_camera& cam, const std::vector<Detection>& detections,
                                    const std::vector<Grasp>& grasps, const Gripper& gripper,
                                    const BinFit* bin, const PickOptions& options);

}  // namespace binpick
