// Everything `binpick bench` measured, as the report (Markdown and JSON) presents it. Times are
// medians over the repetitions; "per hypothesis" divides an image's time by its hypotheses.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace binpick::bench {

struct MachineInfo {
  std::string opencl, vulkan;
  unsigned cores = 0;
  std::string date;            // UTC, ISO 8601
  double stream_gb_s = 0;      // memory-bound peak (STREAM triad) on the OpenCL device
  double fma_gflop_s = 0;      // compute-bound peak (independent FMA chains)
  double gather_mlookup_s = 0; // random 4-byte lookups in a table larger than the caches
  double gather_cached_mlookup_s = 0;  // the same in a table that fits a core's L2
  double int_gop_s = 0;        // 32-bit integer operations
};

struct SynthBin {
  int bin = 0;
  double physics_s = 0, render_s = 0, decompose_s = 0, write_s = 0;
  bool measured_now = true;  // false: read back from an earlier run's record
};

struct TrainMeasure {
  double voxel_ratio = 0;
  std::size_t points = 0, entries = 0;
  double ms = 0;  // median
};

// Work done by the voting of one or more hypotheses (counted, not timed).
struct PairCounts {
  double pairs = 0;      // reference x scene point pairs whose feature is computed
  double lookups = 0;    // pairs within the model's diameter: one hash lookup each
  double votes = 0;      // model entries voted for (sum of the looked-up buckets)
  double cells = 0;      // accumulator cells cleared and scanned for peaks
  PairCounts& operator+=(const PairCounts& o);
};

struct StageRow {
  std::string stage;     // as the pipeline names it (points, lowpass, hypotheses, crop, ...)
  double ms_per_hyp = 0; // median over repetitions
};

struct DetectMeasure {
  double ref_ratio = 0;
  std::size_t hypotheses = 0;      // per repetition, over all bins
  double prepare_ms = 0, hypotheses_ms = 0, vote_ms = 0, cluster_ms = 0;  // per hypothesis
  double total_ms = 0;
  std::size_t images = 0;
  double ms_per_image = 0;         // every stage of an image, median over repetitions
  std::vector<StageRow> stages;
  PairCounts counts;               // per hypothesis (mean)
  double features_ms = 0, votes_ms = 0, peaks_ms = 0;  // per hypothesis, parts of vote_ms
  double precision_top = 0, precision_all = 0;          // at (10 %, 15 deg)
  double precision_top_strict = 0, precision_all_strict = 0;  // at (5 %, 5 deg)
};

struct ScalingPoint {
  double x = 0;        // the varied quantity
  double size = 0;     // what it gives (points, reference points, model points)
  double ms = 0;       // per hypothesis, median
  double extra = 0;    // a second quantity when useful (model entries)
};

struct Scaling {
  std::string name, x_label, size_label;
  std::vector<ScalingPoint> points;
  double exponent = 0;  // slope of log(ms) against log(size), least squares
};

struct OpenCvSide {
  double ref_ratio = 0;
  std::size_t crops = 0;
  double binpick_ms = 0, opencv_ms = 0;  // per crop: voting + clustering vs match()
  double binpick_top = 0, binpick_all = 0, opencv_top = 0, opencv_all = 0;
};

struct OpenCvComparison {
  bool ran = false;
  std::string why_not;      // when !ran
  std::string version;
  std::string runner;
  double binpick_train_ms = 0, opencv_train_ms = 0;
  std::vector<OpenCvSide> sides;
};

struct BenchResult {
  MachineInfo machine;
  std::string part, scene;  // "builtin:bracket", "1600 x 900, 350 parts, 3 bins"
  int repeats = 0;
  std::vector<SynthBin> synth;
  TrainMeasure train;
  std::vector<DetectMeasure> detect;
  // The same bins seen by the real-size camera, at the defaults (BenchOptions::real_width).
  std::optional<DetectMeasure> real;
  std::string real_scene;
  std::vector<Scaling> scaling;
  OpenCvComparison opencv;
  double seconds = 0;  // the whole bench
};

}  // namespace binpick::bench
