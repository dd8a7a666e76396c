// What `binpick tune` searches: a point is the detection parameters plus the model's feature
// quantisation (distance and angle steps, which live in the trained model, so a point with other
// steps needs its own model). The axes are the parameters varied, each with the values tried.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "host/detect/detector.hpp"
#include "kernels/binpick_shared.h"

namespace binpick {

struct TunePoint {
  DetectParams detect;
  std::uint32_t distance_steps = BP_PPF_DEFAULT_DIST_STEPS;
  std::uint32_t angle_steps = BP_PPF_DEFAULT_ANGLE_STEPS;
};

// Equal when every parameter is (exactly: values come from the axes or the start).
bool same_point(const TunePoint& a, const TunePoint& b);

// The canonical text of a point: detect's params_json plus the steps. Names its cached results.
std::string point_key(const TunePoint& p);

struct TuneAxis {
  std::string name;            // as the detect/train option, e.g. "ref-ratio"
  std::vector<double> values;  // tried in this order
  std::function<double(const TunePoint&)> get;
  std::function<void(TunePoint&, double)> set;
  bool needs_training = false;  // a value here changes the model
};

// ref-ratio, cluster-distance, cluster-angle, exclusion-ratio, angle-steps, distance-steps: the
// cheap detection parameters first, the ones that need a model of their own last.
const std::vector<TuneAxis>& tune_axes();

}  // namespace binpick
