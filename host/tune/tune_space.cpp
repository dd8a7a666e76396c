#include "host/tune/tune_space.hpp"

#include <fmt/format.h>

#include "host/detect/params/params_file.hpp"

namespace binpick {
namespace {

TuneAxis detect_axis(std::string name, std::vector<double> values, double DetectParams::*member) {
  return {std::move(name), std::move(values),
          [member](const TunePoint& p) { return p.detect.*member; },
          [member](TunePoint& p, double v) { p.detect.*member = v; }, false};
}

TuneAxis steps_axis(std::string name, std::vector<double> values, std::uint32_t TunePoint::*member) {
  return {std::move(name), std::move(values),
          [member](const TunePoint& p) { return double(p.*member); },
          [member](TunePoint& p, double v) { p.*member = static_cast<std::uint32_t>(v); }, true};
}

}  // namespace

bool same_point(const TunePoint& a, const TunePoint& b) { return point_key(a) == point_key(b); }

std::string point_key(const TunePoint& p) {
  return fmt::format("{{\"detect\": {}, \"distance-steps\": {}, \"angle-steps\": {}}}",
                     params_json(p.detect), p.distance_steps, p.angle_steps);
}

const std::vector<TuneAxis>& tune_axes() {
  // The values around the paper's (docs/parameters.md): 2 % and 20 % reference points, 12-degree angle
  // steps, 20 distance steps, clustering at 14.4 % and 20 degrees, exclusion 1.2 diameters.
  static const std::vector<TuneAxis> axes = {
      detect_axis("ref-ratio", {0.02, 0.05, 0.1, 0.2, 0.3}, &DetectParams::ref_ratio),
      detect_axis("cluster-distance", {0.07, 0.144, 0.25}, &DetectParams::cluster_distance),
      detect_axis("cluster-angle", {10, 20, 30}, &DetectParams::cluster_angle),
      detect_axis("exclusion-ratio", {1.0, 1.2, 1.5}, &DetectParams::exclusion_ratio),
      steps_axis("angle-steps", {20, 30, 45}, &TunePoint::angle_steps),
      steps_axis("distance-steps", {10, 20, 30}, &TunePoint::distance_steps),
  };
  return axes;
}

}  // namespace binpick
