// A progress bar on stderr for long work (synthesis, batch detection). On a terminal it redraws
// one line at most ten times a second; in a log or CI (not a terminal) it prints a plain line at
// every tenth of the work, so batch runs stay readable. A listener (the Python module's
// callback) takes every update instead of stderr.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>

namespace binpick {

// One step of a Progress: its label, how much of its total is done and what it is at; finished:
// the work is done and status is its summary.
struct ProgressEvent {
  std::string_view label;
  std::size_t done = 0, total = 0;
  std::string_view status;
  bool finished = false;
};
using ProgressListener = std::function<void(const ProgressEvent&)>;

// While one lives, the progress of its thread goes to the listener, not stderr (none drawn). The
// listener's exceptions pass out of Progress::update and finish (the work stops there).
class ScopedProgressListener {
 public:
  explicit ScopedProgressListener(ProgressListener listener);
  ~ScopedProgressListener();
  ScopedProgressListener(const ScopedProgressListener&) = delete;
  ScopedProgressListener& operator=(const ScopedProgressListener&) = delete;

 private:
  ProgressListener previous_;
};

class Progress {
 public:
  Progress(std::string label, std::size_t total);
  ~Progress();  // ends the line if finish() was not called; never throws
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void update(std::size_t done, std::string_view status = {});
  // Replaces the bar by one summary line.
  void finish(std::string_view summary);

  static bool enabled();  // false under BINPICK_QUIET=1

 private:
  void draw(std::string_view status, bool force);

  std::string label_;
  std::size_t total_, done_ = 0;
  bool terminal_, finished_ = false;
  int last_tenth_ = -1;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace binpick
