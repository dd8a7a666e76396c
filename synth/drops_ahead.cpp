#include "synth/drops_ahead.hpp"

#include <atomic>
#include <chrono>
#include <mutex>
#include <optional>
#include <thread>

#include "host/core/timing.hpp"

namespace binpick {

// What a drop's thread tells the caller's: its last wave, and whether to stop.
struct DropsAhead::Watch {
  std::mutex mutex;
  std::optional<DropProgress> last;
  std::atomic<bool> cancel{false};
};

namespace {
struct Cancelled {};  // thrown through drop_parts by its progress callback; never seen outside
}  // namespace

unsigned DropsAhead::threads_for(unsigned requested) {
  return requested > 0 ? requested : std::max(1u, std::thread::hardware_concurrency());
}

DropsAhead::DropsAhead(const std::vector<DropKind>& kinds, std::vector<Request> requests,
                       unsigned threads)
    : kinds_(kinds), requests_(std::move(requests)), threads_(threads_for(threads)) {}

DropsAhead::~DropsAhead() {
  for (Running& r : running_) r.watch->cancel = true;
  for (Running& r : running_) r.pile.wait();  // its exception, Cancelled or other, dropped
}

void DropsAhead::start_more() {
  while (running_.size() < threads_ && started_ < requests_.size()) {
    const Request* request = &requests_[started_++];
    auto watch = std::make_shared<Watch>();
    const std::vector<DropKind>* kinds = &kinds_;
    running_.push_back({std::async(std::launch::async,
                                   [kinds, request, watch] {
                                     Stopwatch clock;
                                     DropResult pile = drop_parts(
                                         *kinds, request->sequence, request->drop,
                                         [&watch](const DropProgress& p) {
                                           if (watch->cancel) throw Cancelled{};
                                           const std::lock_guard lock(watch->mutex);
                                           watch->last = p;
                                         });
                                     return Dropped{std::move(pile), clock.lap_seconds()};
                                   }),
                        watch});
  }
}

DropsAhead::Dropped DropsAhead::next(const ProgressFn& progress) {
  start_more();
  if (running_.empty()) throw std::logic_error("DropsAhead::next: no request left");
  Running& first = running_.front();
  while (first.pile.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready) {
    std::optional<DropProgress> last;
    {
      const std::lock_guard lock(first.watch->mutex);
      last = first.watch->last;
    }
    if (last && progress) progress(*last);
  }
  Running done = std::move(first);
  running_.pop_front();
  start_more();  // the next bin drops while the caller renders this one
  return done.pile.get();
}

}  // namespace binpick
