// Independent host work split over two threads. The detector's host stages (bin fit, the
// rival cap) run while the OpenCL device idles, on machines with a few cores; a second thread
// halves them. Each half must write only its own outputs, so that the result is the same as one
// thread's.
#pragma once

#include <cstddef>
#include <future>

namespace binpick {

// run(first, last) over [0, n / 2) on this thread and [n / 2, n) on a second one; returns when
// both are done, rethrowing the first half's exception, else the second's.
template <class Run>
void in_two_halves(std::size_t n, const Run& run) {
  std::future<void> second = std::async(std::launch::async, [&run, n] { run(n / 2, n); });
  run(0, n / 2);
  second.get();
}

}  // namespace binpick
