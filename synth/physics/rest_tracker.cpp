#include "synth/physics/rest_tracker.hpp"

#include <algorithm>
#include <cmath>

namespace binpick {
namespace {

// Long enough to cancel the jitter of resting contacts (0.05 s was not), short enough that a
// part tipping over still shows within a rest time.
constexpr double kWindowSeconds = 0.25;

// The angle (rad) of the turn from a to b, in double: through the vector part of a^-1 b
// (sin of half the angle), which stays accurate for the small turns that matter here, where
// an arc cosine of the dot product loses them in float rounding.
double turn_angle(const btQuaternion& a, const btQuaternion& b) {
  const double aw = a.w(), ax = a.x(), ay = a.y(), az = a.z();
  const double bw = b.w(), bx = b.x(), by = b.y(), bz = b.z();
  const double w = aw * bw + ax * bx + ay * by + az * bz;
  const double x = aw * bx - bw * ax - (ay * bz - az * by);
  const double y = aw * by - bw * ay - (az * bx - ax * bz);
  const double z = aw * bz - bw * az - (ax * by - ay * bx);
  return 2.0 * std::atan2(std::sqrt(x * x + y * y + z * z), std::abs(w));
}

}  // namespace

RestTracker::RestTracker(double linear_speed, double angular_speed, double rest_seconds)
    : linear_speed_(linear_speed), angular_speed_(angular_speed), rest_seconds_(rest_seconds) {}

RestTracker::Motion RestTracker::start_at(const btTransform& pose, bool still_before) {
  Motion m;
  if (still_before) m.window.push_back({-kWindowSeconds, pose.getOrigin(), pose.getRotation()});
  m.window.push_back({0.0, pose.getOrigin(), pose.getRotation()});
  return m;
}

void RestTracker::add(const btTransform& pose) { parts_.push_back(start_at(pose, false)); }

void RestTracker::update(std::size_t index, const btTransform& pose, double dt) {
  Motion& m = parts_[index];
  const double now = m.window.back().time + dt;
  m.window.push_back({now, pose.getOrigin(), pose.getRotation()});
  // Keep the newest poses that span the window (all of them until they do: a part just
  // released is judged on what it did since, a thawed one as still before).
  while (m.window.size() > 2 && now - m.window[1].time >= kWindowSeconds) m.window.pop_front();
  const Sample& first = m.window.front();
  const double seconds = now - first.time;
  const double moved = (pose.getOrigin() - first.position).length();
  m.ratio = std::max(moved / seconds / linear_speed_,
                     turn_angle(first.orientation, m.window.back().orientation) / seconds /
                         angular_speed_);
  m.calm_seconds = m.ratio < 1.0 ? m.calm_seconds + dt : 0.0;
}

void RestTracker::restart(std::size_t index, const btTransform& pose) {
  parts_[index] = start_at(pose, true);
}

double RestTracker::speed_ratio(std::size_t index) const { return parts_[index].ratio; }

bool RestTracker::at_rest(std::size_t index) const {
  return parts_[index].calm_seconds >= rest_seconds_;
}

}  // namespace binpick
