// Detection stage by stage on the benchmark's scenes: the production path
// (Detector::detect on each depth image), repeated, timed per stage and per hypothesis, with
// the work counted for throughput and the results evaluated against the ground truth. The
// neighbourhoods each hypothesis voted on are kept: the scaling sweeps and OpenCV's runner get
// exactly these crops.
#pragma once

#include <filesystem>
#include <vector>

#include "bench/lib/bench_result.hpp"
#include "host/formats/bop/results_csv.hpp"
#include "host/detect/detector.hpp"
#include "host/eval/metrics/eval_dataset.hpp"
#include "host/detect/scene/depth_to_points.hpp"

namespace binpick::bench {

struct BenchScene {
  int scene_id = 0;
  DepthImage depth;
  bp_camera camera{};
};

// Image 0 of every scene of DATASET/test.
std::vector<BenchScene> load_bench_scenes(const std::filesystem::path& dataset);

// One hypothesis' neighbourhood, subsampled at the model's voxel, with its result.
struct BenchCrop {
  int scene_id = 0;
  std::uint32_t hypothesis = 0;  // rank by height within its image
  PointCloud cloud;
  Detection detection;           // binpick's, at the measure's ref ratio (votes 0: none)
};

struct StageRun {
  DetectMeasure measure;
  std::vector<BenchCrop> crops;        // in scene, then hypothesis order
  std::vector<bop::ResultRow> rows;    // binpick's results (first repetition), for evaluation
};

// params.ref_ratio is used as given. repeats >= 1; the first run after building the programs
// is not timed (warm-up).
StageRun run_stages(const PpfModel& model, const DetectParams& params,
                    const std::vector<BenchScene>& scenes, const eval::Dataset& dataset,
                    int repeats);

// Precision of rows against the dataset at (10 %, 15 deg) and (5 %, 5 deg): top, all.
struct Precision {
  double top = 0, all = 0, top_strict = 0, all_strict = 0;
};
Precision precision_of(const eval::Dataset& dataset, const std::vector<bop::ResultRow>& rows);

double median(std::vector<double> values);

}  // namespace binpick::bench
