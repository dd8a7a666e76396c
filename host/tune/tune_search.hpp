// The search of `binpick tune`, independent of how a point is measured: coordinate descent over
// tune_axes() from a starting point. Each round tries every value of each axis in turn with the
// other parameters at the best point so far and moves to the best; it stops after a round that
// found nothing better, after `rounds` rounds, or at `max_evals` evaluations. No point is
// measured twice. The order is fixed, so the search is deterministic for a deterministic measure
// (time per hypothesis is measured, so only exact precision ties can go either way).
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "host/tune/tune_space.hpp"

namespace binpick {

struct TuneScore {
  double top = 0, all = 0;                // precision at the loose point (10 %, 15 deg)
  double strict_top = 0, strict_all = 0;  // at the strict point (5 %, 5 deg)
  double ms_per_hypothesis = 0;
};

// Measured times of the same work differ by a few per cent from run to run: a point wins on
// time only when it is faster by more than this fraction.
inline constexpr double kTimeTolerance = 0.05;

// True if a is strictly better than b under the budget (ms per hypothesis): a point within it
// beats one over it; within it, higher top precision wins, then higher strict top precision,
// then (on a small dataset the top-voted ones often tie) higher precision of all hypotheses,
// loose then strict, then less time (by more than kTimeTolerance); over it, less time wins (the
// least bad if nothing fits).
bool better(const TuneScore& a, const TuneScore& b, double budget_ms);

struct TuneRow {
  std::size_t index = 0;  // 0 = the starting point
  int round = 0;          // 0 for the start, then 1, 2, ...
  std::string axis;       // the axis varied ("start" for the first row)
  TunePoint point;
  TuneScore score;
  bool within_budget = false;
};

struct SearchOptions {
  double budget_ms = 50;
  int rounds = 2;
  int max_evals = 40;
};

struct SearchResult {
  std::vector<TuneRow> rows;  // in evaluation order
  std::size_t best = 0;       // index into rows
};

using MeasureFn = std::function<TuneScore(const TunePoint&)>;
// Called after each measurement with its row and the index of the best row so far.
using RowFn = std::function<void(const TuneRow&, std::size_t best)>;

// InputError for a budget that is not positive and finite, or rounds / max_evals below 1.
void check(const SearchOptions& options);

// Measures `start`, then searches; on_row is called after each measurement.
SearchResult coordinate_descent(const TunePoint& start, const SearchOptions& options,
                                const MeasureFn& measure, const RowFn& on_row = {});

// Upper bound of the measurements a search can make (for a progress bar).
std::size_t max_measurements(const SearchOptions& options);

}  // namespace binpick
