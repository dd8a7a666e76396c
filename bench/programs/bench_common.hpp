// What every benchmark program shares: the smoke switch (ctest runs each program once, quickly,
// with BINPICK_BENCH_SMOKE set) and the process's CPU time.
#pragma once

#include <sys/resource.h>

#include <cstdlib>

namespace binpick::bench {

// True under ctest's smoke run: small inputs, one repetition.
inline bool smoke() { return std::getenv("BINPICK_BENCH_SMOKE") != nullptr; }

// CPU time of the whole process (PoCL's threads included), ms: on a shared machine the wall
// clock also counts other people's work.
inline double process_cpu_ms() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return (u.ru_utime.tv_sec + u.ru_stime.tv_sec) * 1e3 +
         (u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-3;
}

}  // namespace binpick::bench
