#include "synth/physics/rest_tracker.hpp"

#include <algorithm>

namespace binpick {
namespace {

// Long enough to cancel the jitter of resting contacts (0.05 s was not), short enough that a
// part tipping over still shows within a rest time.
constexpr double kAveragingSeconds = 0.25;

}  // namespace

RestTracker::RestTracker(double linear_speed, double angular_speed, double rest_seconds)
    : linear_speed_(linear_speed), angular_speed_(angular_speed), rest_seconds_(rest_seconds) {}

void RestTracker::add() { parts_.emplace_back(); }

void RestTracker::update(std::size_t index, const btVector3& linear, const btVector3& angular,
                         double dt) {
  Motion& m = parts_[index];
  const auto blend = btScalar(dt / (kAveragingSeconds + dt));  // exponential moving average
  m.linear += blend * (linear - m.linear);
  m.angular += blend * (angular - m.angular);
  m.calm_seconds = speed_ratio(index) < 1.0 ? m.calm_seconds + dt : 0.0;
}

void RestTracker::restart(std::size_t index) { parts_[index].calm_seconds = 0.0; }

double RestTracker::speed_ratio(std::size_t index) const {
  const Motion& m = parts_[index];
  return std::max(m.linear.length() / linear_speed_, m.angular.length() / angular_speed_);
}

bool RestTracker::at_rest(std::size_t index) const {
  return parts_[index].calm_seconds >= rest_seconds_;
}

}  // namespace binpick
