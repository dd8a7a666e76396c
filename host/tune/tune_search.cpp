#include "host/tune/tune_search.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "host/core/error.hpp"

namespace binpick {

bool better(const TuneScore& a, const TuneScore& b, double budget_ms) {
  const bool a_in = a.ms_per_hypothesis <= budget_ms, b_in = b.ms_per_hypothesis <= budget_ms;
  if (a_in != b_in) return a_in;
  if (!a_in) return a.ms_per_hypothesis < b.ms_per_hypothesis;
  if (a.top != b.top) return a.top > b.top;
  if (a.strict_top != b.strict_top) return a.strict_top > b.strict_top;
  if (a.all != b.all) return a.all > b.all;
  if (a.strict_all != b.strict_all) return a.strict_all > b.strict_all;
  return a.ms_per_hypothesis < b.ms_per_hypothesis * (1 - kTimeTolerance);
}

void check(const SearchOptions& o) {
  if (!(std::isfinite(o.budget_ms) && o.budget_ms > 0))
    throw InputError(fmt::format("--budget-ms {} must be a positive time per hypothesis (ms)",
                                 o.budget_ms));
  if (o.rounds < 1 || o.rounds > 100)
    throw InputError(fmt::format("--rounds {} must be in [1, 100]", o.rounds));
  if (o.max_evals < 1 || o.max_evals > 10000)
    throw InputError(fmt::format("--max-evals {} must be in [1, 10000]", o.max_evals));
}

std::size_t max_measurements(const SearchOptions& o) {
  std::size_t per_round = 0;
  for (const TuneAxis& axis : tune_axes()) per_round += axis.values.size();
  return std::min<std::size_t>(o.max_evals, 1 + std::size_t(o.rounds) * per_round);
}

SearchResult coordinate_descent(const TunePoint& start, const SearchOptions& o,
                                const MeasureFn& measure, const RowFn& on_row) {
  check(o);
  SearchResult r;
  const auto add = [&](const TunePoint& p, int round, const std::string& axis) {
    TuneRow row;
    row.index = r.rows.size();
    row.round = round;
    row.axis = axis;
    row.point = p;
    row.score = measure(p);
    row.within_budget = row.score.ms_per_hypothesis <= o.budget_ms;
    r.rows.push_back(row);
    if (row.index > 0 && better(row.score, r.rows[r.best].score, o.budget_ms)) r.best = row.index;
    if (on_row) on_row(r.rows.back(), r.best);
  };
  const auto seen = [&](const TunePoint& p) {
    return std::any_of(r.rows.begin(), r.rows.end(),
                       [&](const TuneRow& row) { return same_point(row.point, p); });
  };

  add(start, 0, "start");
  for (int round = 1; round <= o.rounds; ++round) {
    const std::size_t best_before = r.best;
    for (const TuneAxis& axis : tune_axes()) {
      // Every value of this axis with the others at the best point so far: the best may move
      // while the axis is scanned, but the scan stays anchored where it began.
      const TunePoint anchor = r.rows[r.best].point;
      for (double value : axis.values) {
        if (r.rows.size() >= std::size_t(o.max_evals)) return r;
        TunePoint p = anchor;
        axis.set(p, value);
        if (!seen(p)) add(p, round, axis.name);
      }
    }
    if (r.best == best_before) break;  // a whole round found nothing better: a local optimum
  }
  return r;
}

}  // namespace binpick
