// A cap on the PPF table's buckets for voting (DetectParams::bucket_cap).
//
// Why: a flat face makes most of a part's pairs coplanar, and coplanar pairs of one distance
// share one key, so on a flush stack of plates a scene pair hits thousands of table entries and
// voting is slow. Those entries say little about where
// the part is in its plane, while the rarer keys of its rim and holes do. A bucket with more
// entries than the cap keeps the cap's worth, evenly spaced: every reference point of the
// bucket keeps its share, and the common keys weigh less against the rare ones. Off by default:
// it is faster on flat parts but lost a few hypotheses (docs/decisions/2026-11-25-bucket-cap.md).
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
