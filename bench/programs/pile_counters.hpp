// The counters that say whether a dropped pile is realistic, shared by the physics benchmarks:
// simulated seconds, the deepest overlap of two parts, and how many parts move (over 1 and 5 mm,
// and the most) when the whole pile is simulated on for a second (after the timed loop).
#pragma once

#include <benchmark/benchmark.h>

#include "synth/physics/drop.hpp"
#include "synth/physics/penetration.hpp"
#include "synth/physics/settle_drift.hpp"

namespace binpick::bench {

inline void add_pile_counters(benchmark::State& state, const ConvexParts& hulls, const Mesh& part,
                              const DropOptions& options, const DropResult& result) {
  state.counters["sim_s"] = result.stats.simulated_seconds;
  state.counters["overlap_mm"] = deepest_penetration_mm(hulls, result.poses);
  const SettleDrift drift = settle_drift(hulls, part, options, result.poses);
  state.counters["drift_1mm"] = drift.moved_over_1mm;
  state.counters["drift_5mm"] = drift.moved_over_5mm;
  state.counters["drift_max_mm"] = drift.worst_mm;
}

}  // namespace binpick::bench
