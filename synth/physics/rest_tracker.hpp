// Whether each part is at rest: how far it went over the last quarter second (its centre of
// mass and its orientation), over that time, stayed under the rest speeds for rest_seconds
// (docs/synthesis.md).
//
// Displacement, not velocity. Parts resting on each other jitter: Bullet's contact solver kicks
// a resting part back and forth from step to step, its speed spiking over any useful threshold
// while it goes nowhere. And in a deep pile the solver does not converge in its iterations: a
// part keeps a velocity into its supports that the solver's position correction (split
// impulse) undoes every step, so the velocity says it sinks while it stays put, and a deep
// pile of plates never came to rest. The pose itself shows only what the part did.
//
// A plain sliding window (the displacement over the window, over its length), not an
// exponential average: a part that lands and stops reads as stopped one window later, where an
// exponential average still read it as moving (and pushing its neighbours awake,
// pile_freezer.hpp) for over a second. Magnitudes of the displacement and of the turn, so that
// motion in any direction counts. Figures: docs/decisions/2026-11-24-rest-by-displacement.md.
#pragma once

#include <LinearMath/btTransform.h>

#include <cstddef>
#include <deque>
#include <vector>

namespace binpick {

class RestTracker {
 public:
  // Speeds in units/s and rad/s.
  RestTracker(double linear_speed, double angular_speed, double rest_seconds);

  // Starts tracking part `index` (the next one), released at rest at `pose` (units).
  void add(const btTransform& pose);
  // The pose at the end of a step of length dt (s).
  void update(std::size_t index, const btTransform& pose, double dt);
  // The frozen part `index` is dynamic again at `pose` (pile_freezer.hpp): it has to be calm
  // for rest_seconds again, and its window starts full of that pose, since it was still while
  // frozen. Judged only on the few steps since, a thawed part that jiggled by a hundredth of a
  // millimetre read as fast enough to push its frozen neighbours awake, and they theirs: in a
  // pile of flat plates one landing wave woke the whole pile.
  void restart(std::size_t index, const btTransform& pose);

  // The larger of the window's speeds over their rest speeds: below 1 is calm.
  double speed_ratio(std::size_t index) const;
  // Calm for rest_seconds.
  bool at_rest(std::size_t index) const;

 private:
  struct Sample {
    double time;  // s, on the part's own clock since it was added or restarted
    btVector3 position;
    btQuaternion orientation;
  };
  struct Motion {
    std::deque<Sample> window;  // the poses spanning the last kWindowSeconds, oldest first
    double ratio = 0.0;         // speed_ratio after the last update
    double calm_seconds = 0.0;  // how long ratio has been below 1
  };
  // A part at `pose`; still there for the last window if `still_before`.
  static Motion start_at(const btTransform& pose, bool still_before);

  double linear_speed_, angular_speed_, rest_seconds_;
  std::vector<Motion> parts_;
};

}  // namespace binpick
