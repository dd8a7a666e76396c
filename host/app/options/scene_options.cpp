#include "host/app/options/scene_options.hpp"
#include <CLI/CLI.hpp>

#include "synth/part_mix.hpp"
#include "synth/sensor/sensor_options.hpp"

namespace binpick::cli {

void add_scene_options(CLI::App* verb, SceneArgs& a) {
  verb->add_option("--bin-render", a.bin_render,
                   "full: the camera sees the bin (floor, walls, rim) as well as the parts; none: "
                   "the parts alone, as in the paper (the parts collide with the bin either way)")
      ->check(CLI::IsMember({"full", "none"}))
      ->capture_default_str();
  verb->add_option("--distractors", a.distractors,
                   "other parts mixed into the bin, MODEL[:FRACTION],... (MODEL a file in mm or "
                   "builtin:NAME; FRACTION of --objects, default 0.25 split evenly over the "
                   "distractors given); obj_ids 2, 3, ... in this order");
  verb->add_option("--camera-tilt", a.camera_tilt_deg,
                   "turn the camera about the bin's x axis through the centre of the bin floor, "
                   "which stays on the optical axis at --camera-height; positive moves the "
                   "camera towards -y, looking at the +y wall (degrees, -80 to 80)")
      ->capture_default_str();
  verb->add_option("--camera-roll", a.camera_roll_deg,
                   "then turn the camera about its optical axis: the bin shows turned by this "
                   "much in the image, counter-clockwise (degrees, -180 to 180)")
      ->capture_default_str();
  add_sensor_options(verb, a.sensor);
}

void apply_scene_args(const SceneArgs& a, SynthOptions& o) {
  o.bin_render = a.bin_render == "none" ? BinRender::none : BinRender::full;
  if (!a.distractors.empty()) o.distractors = parse_distractors(a.distractors);
  o.camera_tilt_deg = a.camera_tilt_deg;
  o.camera_roll_deg = a.camera_roll_deg;
  o.sensor = a.sensor;
}

}  // namespace binpick::cli
