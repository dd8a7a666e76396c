#include "host/tune/tune_replay.hpp"

#include <algorithm>

namespace binpick {
namespace {

// Thrown out of the search at the first point without a measurement.
struct Unmeasured {
  TunePoint point;
};

}  // namespace

SearchReplay replay_search(const TunePoint& start, const SearchOptions& options,
                           const LookupFn& lookup) {
  std::vector<TunePoint> measured;  // the points the search went through, in order
  std::size_t best = 0;
  const auto measure = [&](const TunePoint& p) {
    const std::optional<TuneScore> score = lookup(p);
    if (!score) throw Unmeasured{p};
    return *score;
  };
  const auto on_row = [&](const TuneRow& row, std::size_t best_row) {
    measured.push_back(row.point);
    best = best_row;
  };
  try {
    return {coordinate_descent(start, options, measure, on_row), {}};
  } catch (const Unmeasured& missing) {
    std::vector<TunePoint> next{missing.point};
    const auto known = [&](const TunePoint& p) {
      const auto same = [&](const TunePoint& q) { return same_point(p, q); };
      return std::any_of(measured.begin(), measured.end(), same) ||
             std::any_of(next.begin(), next.end(), same);
    };
    const TunePoint anchor = measured.empty() ? start : measured[best];
    const std::size_t room = std::size_t(options.max_evals) - measured.size();
    for (const TuneAxis& axis : tune_axes())
      for (double value : axis.values) {
        TunePoint p = anchor;
        axis.set(p, value);
        if (next.size() < room && !known(p) && !lookup(p)) next.push_back(p);
      }
    return {std::nullopt, next};
  }
}

}  // namespace binpick
