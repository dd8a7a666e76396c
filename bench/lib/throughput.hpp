// Stage times turned into rates in the units of the work, and each rate as a fraction of what
// the OpenCL device measured on a plain kernel of the same kind (machine_peak.hpp):
//   features: pair features per second; each pair is about kFeatureFlopsPerPair floating-point
//             operations, compared with the FMA peak (compute-bound);
//   voting:   hash lookups and votes per second; every lookup and every vote is one access at
//             a data-dependent address, compared with the random-gather peak of a table in L2
//             (a reference point's accumulator is L2-sized; the model's table is a few MB);
//   peaks:    accumulator cells scanned per second, 4 bytes each, compared with the stream
//             bandwidth (memory-bound).
#pragma once

#include "bench/lib/bench_result.hpp"

namespace binpick::bench {

// bp_ppf_pair8 counted by hand, per pair (lane): 4 atan2 (~20 each, as polynomial + division), 3 cross products
// (9), 4 dot/length (5-6 each), 4 quantisations (~4), the alpha rotation (~25). An estimate: the
// report says so.
inline constexpr double kFeatureFlopsPerPair = 160.0;

struct Throughput {
  double pairs_per_s = 0, lookups_per_s = 0, votes_per_s = 0, cells_per_s = 0;
  double features_of_fma_peak = 0;    // fraction
  double voting_of_gather_peak = 0;   // fraction
  double peaks_of_stream_peak = 0;    // fraction
};

Throughput throughput(const DetectMeasure& m, const MachineInfo& machine);

}  // namespace binpick::bench
