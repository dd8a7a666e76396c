#include "host/detect/batch/picks_csv.hpp"

#include <fmt/format.h>

#include "host/core/csv_quote.hpp"

namespace binpick {

std::filesystem::path picks_path(const std::filesystem::path& out) {
  std::filesystem::path p = out;
  return p.replace_extension(".picks.csv");
}

std::string pick_rows(const std::vector<Detection>& detections, int scene_id, int im_id,
                      int obj_id, const std::string& gripper) {
  std::string text;
  for (std::size_t r = 0; r < detections.size(); ++r) {
    const Detection& d = detections[r];
    const PlannedPick& p = d.pick;
    if (!p.picked) {
      text += fmt::format("{},{},{},{},,,,,,,,{:.6f},{},{}\n", scene_id, im_id, obj_id, r, d.score(),
                          csv_quoted(gripper), csv_quoted(p.reason));
      continue;
    }
    const Eigen::Matrix3d R = p.pose.linear();
    const Eigen::Vector3d t = p.pose.translation(), a = R.col(2);
    text += fmt::format(
        "{},{},{},{},{},{},{:.6f} {:.6f} {:.6f} {:.6f} {:.6f} {:.6f} {:.6f} {:.6f} {:.6f},"
        "{:.3f} {:.3f} {:.3f},{:.6f} {:.6f} {:.6f},{:.3f},{:.3f},{:.6f},{},\n",
        scene_id, im_id, obj_id, r, p.order, p.grasp, R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1),
        R(1, 2), R(2, 0), R(2, 1), R(2, 2), t.x(), t.y(), t.z(), a.x(), a.y(), a.z(), p.width, p.clearance,
        d.score(), csv_quoted(gripper));
  }
  return text;
}

}  // namespace binpick
