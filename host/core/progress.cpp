#include "host/core/progress.hpp"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>

#include <fmt/format.h>
#include <unistd.h>

#include "host/core/timing.hpp"

namespace binpick {
namespace {

constexpr int kBarWidth = 28;

thread_local ProgressListener current_listener;

}  // namespace

ScopedProgressListener::ScopedProgressListener(ProgressListener listener)
    : previous_(std::exchange(current_listener, std::move(listener))) {}

ScopedProgressListener::~ScopedProgressListener() { current_listener = std::move(previous_); }

bool Progress::enabled() {
  const char* quiet = std::getenv("BINPICK_QUIET");
  return !(quiet && *quiet && std::string(quiet) != "0");
}

Progress::Progress(std::string label, std::size_t total)
    : label_(std::move(label)), total_(total), terminal_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

Progress::~Progress() {
  if (!finished_ && !current_listener && terminal_ && enabled()) std::fputs("\n", stderr);
}

void Progress::update(std::size_t done, std::string_view status) {
  done_ = done;
  if (current_listener) return current_listener({label_, done_, total_, status, false});
  draw(status, false);
}

void Progress::draw(std::string_view status, bool force) {
  if (!enabled()) return;
  const double fraction = total_ ? double(std::min(done_, total_)) / double(total_) : 1.0;
  if (terminal_) {
    const auto now = std::chrono::steady_clock::now();
    if (!force && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    const int filled = int(fraction * kBarWidth + 0.5);
    std::string line = fmt::format("\r{} [{}{}] {}/{} {:.0f}s {}", label_, std::string(filled, '#'),
                                   std::string(kBarWidth - filled, '.'), done_, total_,
                                   seconds_since(start_), status);
    std::fputs(fmt::format("{:<100}", line).c_str(), stderr);  // pad over a longer old line
    std::fflush(stderr);
  } else {
    const int tenth = int(fraction * 10);
    if (!force && tenth == last_tenth_) return;
    last_tenth_ = tenth;
    std::fputs(fmt::format("{} {}/{} ({:.0f}%) {:.1f}s {}\n", label_, done_, total_,
                           fraction * 100, seconds_since(start_), status).c_str(), stderr);
  }
}

void Progress::finish(std::string_view summary) {
  finished_ = true;
  if (current_listener) return current_listener({label_, total_, total_, summary, true});
  if (!enabled()) return;
  std::fputs(fmt::format("{}{} {} ({:.1f}s)\n", terminal_ ? "\r\033[K" : "", label_, summary,
                         seconds_since(start_)).c_str(), stderr);
}

}  // namespace binpick
