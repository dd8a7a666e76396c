// Small steps the Detector's depth-image path (detector.cpp) and cloud path
// (detector_cloud.cpp) share.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "host/core/error.hpp"
#include "host/detect/hypotheses/hypotheses.hpp"
#include "host/detect/scene/scene_crop.hpp"
#include "host/detect/select/detection.hpp"

namespace binpick::detector_steps {

inline void require(bool ok, const std::string& message) {
  if (!ok) throw InputError(message);
}

// The sphere voted on about a hypothesis' point.
inline CropOptions crop_about(const Hypothesis& h, double radius) {
  CropOptions crop;
  crop.centre = h.point;
  crop.radius = float(radius);
  return crop;
}

// The detection of the k-th highest point, before voting.
inline Detection detection_for(const std::vector<Hypothesis>& hyps, std::size_t k) {
  Detection d;
  d.hypothesis = hyps[k];
  d.index = static_cast<std::uint32_t>(k);
  return d;
}

}  // namespace binpick::detector_steps
