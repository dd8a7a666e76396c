// A progress bar on stderr for long work (synthesis, batch detection). On a terminal it redraws
// one line at most ten times a second; in a log or CI (not a terminal) it prints a plain line at
// every tenth of the work, so batch runs stay readable.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>
#include <string_view>

namespace binpick {

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
