// Grasps and grippers as JSON (docs/picks.md), and the gripper options' text:
//   grasps: {"suction": [{"point": [x, y, z], "approach": [x, y, z], "cup_diameter": d}, ...],
//            "parallel": [{"centre": [...], "approach": [...], "closing": [...], "width": w}, ...]}
//   (model frame, mm; approach: the direction the gripper moves in, into the part)
//   gripper: {"suction": {"cup_diameter", "standoff", "body_diameter", "body_length"}} or
//            {"parallel": {"finger_width", "finger_depth", "finger_length", "palm_height"}}
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "host/core/grasp.hpp"
#include "host/core/gripper.hpp"

namespace binpick {

// The grasps of a JSON text; InputError naming `name` and the grasp for anything wrong (a missing
// or non-finite field, a zero approach, a closing axis along the approach, a size not positive).
// Directions are normalised; a closing axis is made exactly perpendicular to the approach.
std::vector<Grasp> parse_grasps_json(std::string_view text, const std::string& name);
std::vector<Grasp> read_grasps_json(const std::filesystem::path& path);
std::string grasps_json(const std::vector<Grasp>& grasps);

// A gripper from its option text: "suction:CUP,STANDOFF,BODY_D,BODY_L",
// "parallel:FINGER_W,FINGER_D,FINGER_L,PALM_H" (mm) or the name of a JSON file as above.
Gripper parse_gripper(const std::string& spec);
// A gripper JSON text; InputError naming `name` for anything wrong.
Gripper parse_gripper_json(std::string_view text, const std::string& name);

}  // namespace binpick
