#include "host/formats/bop/scene_files.hpp"

#include <cctype>

#include <fmt/format.h>

#include "host/core/error.hpp"

namespace binpick::bop {

std::filesystem::path SceneFiles::json(const std::string& stem) const {
  return dir / (sensor.empty() ? stem + ".json" : stem + "_" + sensor + ".json");
}

std::filesystem::path SceneFiles::image(const std::string& kind, int im_id) const {
  return dir / (sensor.empty() ? kind : kind + "_" + sensor) / fmt::format("{:06d}.png", im_id);
}

std::filesystem::path SceneFiles::intensity(int im_id) const {
  const auto gray = image("gray", im_id);
  if (std::filesystem::exists(gray)) return gray;
  const auto rgb = image("rgb", im_id);
  return std::filesystem::exists(rgb) ? rgb : gray;
}

void check_sensor_name(const std::string& name) {
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'))
      throw InputError(fmt::format(
          "--sensor '{}': a sensor name is letters, digits, '-' and '_' (BOP's file suffix, as "
          "in depth_photoneo/)",
          name));
}

}  // namespace binpick::bop
