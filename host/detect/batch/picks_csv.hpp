// OUT.picks.csv of `detect --picks` (docs/picks.md): per detection its pick (the order a
// robot takes them in, the grasp, the grasp's frame and approach in the camera frame, the
// clearance, the gripper it is planned for) or the reason it has none.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "host/detect/select/detection.hpp"

namespace binpick {

std::filesystem::path picks_path(const std::filesystem::path& out);  // OUT with .picks.csv

inline constexpr const char* kPicksCsvHeader =
    "scene_id,im_id,obj_id,rank,order,grasp,R,t,approach,width,clearance,score,gripper,reason\n";

// The rows of one model's detections in one image (rank: the detection's in the results;
// gripper: its option text, Gripper::describe).
std::string pick_rows(const std::vector<Detection>& detections, int scene_id, int im_id, int obj_id,
                      const std::string& gripper);

}  // namespace binpick
