// Wall-clock time: a stopwatch, seconds since a start, and the time per pipeline stage for the
// CLI and the benchmark ("ms per stage"). Each stage ends with a queue finish, so a stage's time
// is the device's work, not an enqueue.
#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace binpick {

struct StageTime {
  std::string stage;  // "points", "normals", "lowpass", "hypotheses", ...
  double ms = 0.0;
};
using StageTimings = std::vector<StageTime>;

// Seconds elapsed since start (steady clock).
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Time since construction or the last lap.
class Stopwatch {
 public:
  // Milliseconds.
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - start_).count();
    start_ = now;
    return ms;
  }
  double lap_seconds() { return lap() / 1e3; }
  // Milliseconds since the last lap (or the start), without starting a new one.
  double elapsed() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_)
        .count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace binpick
