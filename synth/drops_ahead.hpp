// Piles dropped ahead, on other threads, while the caller renders and writes the bins before
// them. Debian's Bullet is built without BT_THREADSAFE (btCreateDefaultTaskScheduler gives no
// scheduler, so btDiscreteDynamicsWorldMt steps on one thread): one world runs on one core, and
// the bins of a dataset, independent worlds, run side by side
// (docs/synthesis.md, "Bins side by side"). Each bin's pile depends only on its own options and
// seed, so the dataset is the same bytes whatever the number of threads.
#pragma once

#include <cstddef>
#include <deque>
#include <future>
#include <memory>
#include <vector>

#include "synth/physics/drop.hpp"

namespace binpick {

class DropsAhead {
 public:
  struct Request {
    DropOptions drop;
    std::vector<int> sequence;  // drop_parts' kinds released in order
  };
  struct Dropped {
    DropResult pile;
    double seconds = 0;  // the drop's own wall time, on its thread
  };

  // `kinds` must outlive this. threads: piles dropped at once (0: one per core).
  DropsAhead(const std::vector<DropKind>& kinds, std::vector<Request> requests, unsigned threads);
  // Stops the drops still running at their next wave and waits for them; never throws.
  ~DropsAhead();
  DropsAhead(const DropsAhead&) = delete;
  DropsAhead& operator=(const DropsAhead&) = delete;

  // The next request's pile, in request order; `progress` hears of its waves on this thread
  // while it waits. Rethrows the drop's exception.
  Dropped next(const ProgressFn& progress);

  static unsigned threads_for(unsigned requested);  // 0: the cores, at least 1

 private:
  struct Watch;
  struct Running {
    std::future<Dropped> pile;
    std::shared_ptr<Watch> watch;
  };
  void start_more();

  const std::vector<DropKind>& kinds_;
  std::vector<Request> requests_;
  std::size_t started_ = 0;
  unsigned threads_;
  std::deque<Running> running_;
};

}  // namespace binpick
