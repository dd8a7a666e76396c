#include "bench/lib/throughput.hpp"

namespace binpick::bench {
namespace {

double rate(double count, double ms) { return ms > 0 ? count / (ms * 1e-3) : 0; }
double fraction(double value, double peak) { return peak > 0 ? value / peak : 0; }

}  // namespace

Throughput throughput(const DetectMeasure& m, const MachineInfo& machine) {
  Throughput t;
  t.pairs_per_s = rate(m.counts.pairs, m.features_ms);
  t.lookups_per_s = rate(m.counts.lookups, m.votes_ms);
  t.votes_per_s = rate(m.counts.votes, m.votes_ms);
  t.cells_per_s = rate(m.counts.cells, m.peaks_ms);
  t.features_of_fma_peak = fraction(t.pairs_per_s * kFeatureFlopsPerPair, machine.fma_gflop_s * 1e9);
  t.voting_of_gather_peak =
      fraction(t.lookups_per_s + t.votes_per_s, machine.gather_cached_mlookup_s * 1e6);
  t.peaks_of_stream_peak = fraction(t.cells_per_s * 4.0, machine.stream_gb_s * 1e9);
  return t;
}

}  // namespace binpick::bench
