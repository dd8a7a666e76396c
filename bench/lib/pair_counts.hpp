// The work voting does on a neighbourhood, counted rather than timed, to turn stage times into
// throughput (pairs, hash lookups and votes per second). Counted with the C++ reference of the
// features, which equals the device's except for pairs within rounding of a bin edge: a few in
// a million, negligible for a rate.
#pragma once

#include "bench/lib/bench_result.hpp"
#include "host/core/mesh.hpp"
#include "host/train/ppf_model.hpp"

namespace binpick::bench {

// Reference points chosen as the detector chooses them (select_reference_points).
PairCounts count_pairs(const PointCloud& subsampled, double ref_ratio, const PpfModel& model);

}  // namespace binpick::bench
