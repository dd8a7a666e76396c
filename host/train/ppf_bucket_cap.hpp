// A cap on the PPF table's buckets for voting (DetectParams::bucket_cap).
//
// Why: a flat face makes most of a part's pairs coplanar, and coplanar pairs of one distance
// share one key. On the built-in plate (318 points) a scene pair hits 2,770 table entries on
// average (the bolt's 312, the shaft's 143), and a flush stack of plates makes nearly every scene
// pair such a pair: voting took 200-500 ms a hypothesis. Those entries say little about where
// the part is in its plane, while the rarer keys of its rim and holes do. A bucket with more
// entries than the cap keeps the cap's worth, evenly spaced: every reference point of the
// bucket keeps its share, and the common keys weigh less against the rare ones. Off by default:
// measured in docs/parameters.md, it is faster on flat parts but lost a few hypotheses.
#pragma once

#include <cstddef>

#include "host/train/ppf_table.hpp"

namespace binpick {

// Entries a bucket may keep for a cap of `ratio` entries per model point (0: no cap; at least
// one entry otherwise).
std::size_t bucket_cap_entries(double ratio, std::size_t model_points);

// The table with every bucket of more than `cap` entries cut to `cap` of them: positions
// floor(j * size / cap), j = 0 .. cap - 1, in their order. cap 0 returns the table unchanged.
PpfTable cap_ppf_buckets(const PpfTable& table, std::size_t cap);

}  // namespace binpick
