// The tuning search when measurements happen elsewhere (`tune --slurm`): the search is replayed
// over the points measured so far; where it reaches a point not measured yet, it stops and names
// the candidates to measure next as one batch (one job array): that point, then every value of
// every axis around the best point so far (the rest of the round, or the next round's, as far as
// they can be told before the missing results are in), without points measured before, at most
// as many as --max-evals leaves. Measuring them and replaying again gives, once nothing is
// missing, exactly the rows a single process would measure: the search is the same function.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "host/tune/tune_search.hpp"

namespace binpick {

// A point's score if it was measured, nullopt if not.
using LookupFn = std::function<std::optional<TuneScore>(const TunePoint&)>;

struct SearchReplay {
  std::optional<SearchResult> result;  // the whole search, when every point it needs is measured
  std::vector<TunePoint> next;         // otherwise the batch to measure next (not empty)
};

SearchReplay replay_search(const TunePoint& start, const SearchOptions& options,
                           const LookupFn& lookup);

}  // namespace binpick
