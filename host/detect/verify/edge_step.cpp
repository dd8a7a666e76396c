#include "host/detect/verify/edge_step.hpp"

#include <algorithm>

namespace binpick {

double edge_step(const ProbeEvidence& e) {
  return std::max(0.0, e.mean + 2.0 * e.standard_error);
}

double edge_factor(double step, double scale, double gate) {
  if (!(scale > 0) || !(gate > 0)) return 1.0;
  return std::min(1.0, std::max(0.0, step) / (scale * gate));
}

}  // namespace binpick
