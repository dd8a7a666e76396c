#include "synth/physics/rest_tracker.hpp"

#include <algorithm>

namespace binpick {
namespace {

// Long enough to cancel the jitter of resting contacts (0.05 s was not), short enough that a
// part tipping over still shows within a rest time.
constexpr double kWindowSeconds = 0.25;

}  // namespace

RestTracker::RestTracker(double linear_speed, double angular_speed, double rest_seconds)
    : linear_speed_(linear_speed), angular_speed_(angular_speed), rest_seconds_(rest_seconds) {}

void RestTracker::add() { parts_.emplace_back(); }

void RestTracker::update(std::size_t index, const btVector3& linear, const btVector3& angular,
                         double dt) {
  Motion& m = parts_[index];
  const Step step{dt, linear * btScalar(dt), angular * btScalar(dt)};
  m.window.push_back(step);
  m.window_seconds += dt;
  m.linear_sum += step.linear;
  m.angular_sum += step.angular;
  // Keep the newest steps that span the window (all of them until they do: a part just
  // released or thawed is judged on what it did since).
  while (m.window.size() > 1 && m.window_seconds - m.window.front().dt >= kWindowSeconds) {
    const Step& old = m.window.front();
    m.window_seconds -= old.dt;
    m.linear_sum -= old.linear;
    m.angular_sum -= old.angular;
    m.window.pop_front();
  }
  const double seconds = m.window_seconds;
  m.ratio = std::max(m.linear_sum.length() / seconds / linear_speed_,
                     m.angular_sum.length() / seconds / angular_speed_);
  m.calm_seconds = m.ratio < 1.0 ? m.calm_seconds + dt : 0.0;
}

void RestTracker::restart(std::size_t index) { parts_[index] = Motion{}; }

double RestTracker::speed_ratio(std::size_t index) const { return parts_[index].ratio; }

bool RestTracker::at_rest(std::size_t index) const {
  return parts_[index].calm_seconds >= rest_seconds_;
}

}  // namespace binpick
