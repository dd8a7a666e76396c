// How detection cost grows: time per hypothesis against the reference ratio and
// against the scene points of a neighbourhood (both on the fixed crops of the stage run), and
// detection and training time against the model's points (retrained at several voxel sizes).
// Each sweep reports the exponent k of time ~ size^k fitted on a log-log scale.
#pragma once

#include <vector>

#include "bench/lib/bench_options.hpp"
#include "bench/lib/stage_bench.hpp"
#include "host/core/mesh.hpp"

namespace binpick::bench {

// Voting + clustering per hypothesis on `crops` at each ratio.
Scaling scale_with_ref_ratio(const PpfModel& model, const DetectParams& params,
                             const std::vector<BenchCrop>& crops,
                             const std::vector<double>& ratios, int repeats);

// Voting + clustering per hypothesis on the part of each crop within fraction f of its radius
// (around its centroid), at params.ref_ratio.
Scaling scale_with_scene_points(const PpfModel& model, const DetectParams& params,
                                const std::vector<BenchCrop>& crops,
                                const std::vector<double>& fractions, int repeats);

// Retrains at each voxel ratio; returns {detection per hypothesis (whole pipeline on the
// scenes), training} against the model's points.
std::vector<Scaling> scale_with_model_points(const Mesh& mesh, const BenchOptions& options,
                                             const std::vector<BenchScene>& scenes);

// Least-squares slope of log(ms) on log(size) over points with both positive; 0 if fewer
// than two such points.
double log_log_slope(const std::vector<ScalingPoint>& points);

}  // namespace binpick::bench
