// Where the files of one BOP scene are. BOP's industrial datasets keep each sensor's images
// and cameras apart with a suffix (depth_photoneo/, scene_camera_photoneo.json,
// scene_gt_photoneo.json, ...); without a sensor the names are the plain ones binpick writes.
#pragma once

#include <filesystem>
#include <string>

namespace binpick::bop {

struct SceneFiles {
  std::filesystem::path dir;  // SPLIT/NNNNNN
  std::string sensor;         // "" or e.g. "photoneo"

  std::filesystem::path scene_camera() const { return json("scene_camera"); }
  std::filesystem::path scene_gt() const { return json("scene_gt"); }
  std::filesystem::path scene_gt_info() const { return json("scene_gt_info"); }
  std::filesystem::path depth(int im_id) const { return image("depth", im_id); }
  // The intensity image: gray/ if the scene has it, else rgb/ (BOP's colour datasets; read as
  // PNG, so a JPEG rgb/ image gives no intensity), else gray/ (which does not exist).
  std::filesystem::path intensity(int im_id) const;

 private:
  std::filesystem::path json(const std::string& stem) const;
  std::filesystem::path image(const std::string& kind, int im_id) const;
};

// InputError unless name is empty or a plain word of letters, digits, '-' and '_' (it becomes
// part of file names).
void check_sensor_name(const std::string& name);

}  // namespace binpick::bop
