// Whether each part is at rest: its linear and angular velocity, averaged over the last quarter
// second, stayed under the rest speeds (in magnitude, so motion in any direction counts,
// docs/synthesis.md) for rest_seconds. Averaged, because parts resting on each other jitter:
// Bullet's contact solver kicks a resting part back and forth from step to step, its speed
// spiking over any useful threshold while it goes nowhere (measured: 3 mm/s and 0.1 rad/s
// for a bracket that moved 0.2 mm in 1.5 s). A raw test, like Bullet's own sleeping test,
// then either never sees a pile at rest or needs thresholds so loose that parts still
// sliding or tipping pass as resting. The average cancels the kicks and keeps the drift.
//
// A plain average over a sliding window (the displacement over the window, over its length),
// not an exponential one: a part that lands at 3 m/s and stops reads as stopped one window
// later, where an exponential average still read it as moving (and pushing its neighbours
// awake, pile_freezer.hpp) for over a second. Measured on the 350-part torus bin: about a
// fifth less time.
#pragma once

#include <LinearMath/btVector3.h>

#include <cstddef>
#include <deque>
#include <vector>

namespace binpick {

class RestTracker {
 public:
  // Speeds in units/s and rad/s.
  RestTracker(double linear_speed, double angular_speed, double rest_seconds);

  // Starts tracking part `index` (the next one), released at rest.
  void add();
  // The velocities at the end of a step of length dt (s).
  void update(std::size_t index, const btVector3& linear, const btVector3& angular, double dt);
  // The part was jolted (or was frozen and is moving again): forget its history; it has to
  // come to rest again.
  void restart(std::size_t index);

  // The larger of the averaged speeds over their rest speeds: below 1 is calm.
  double speed_ratio(std::size_t index) const;
  // Calm for rest_seconds.
  bool at_rest(std::size_t index) const;

 private:
  struct Step {
    double dt;
    btVector3 linear, angular;  // velocity times dt: the step's displacement and rotation
  };
  struct Motion {
    std::deque<Step> window;  // the steps of the last kWindowSeconds, oldest first
    double window_seconds = 0.0;
    btVector3 linear_sum{0, 0, 0}, angular_sum{0, 0, 0};  // over the window
    double ratio = 0.0;         // speed_ratio after the last update
    double calm_seconds = 0.0;  // how long ratio has been below 1
  };
  double linear_speed_, angular_speed_, rest_seconds_;
  std::vector<Motion> parts_;
};

}  // namespace binpick
