// binpick and OpenCV's cv::ppf_match_3d::PPF3DDetector side by side: the same model
// points, the same crops (each hypothesis' subsampled neighbourhood from the stage run), the
// same parameters, the same scenes' ground truth. OpenCV runs in its own executable
// (bench/opencv/opencv_ppf3d, built only when Debian's libopencv-contrib-dev is installed), so
// binpick never links OpenCV: the crops go to it as PLY files and its poses come back as JSON.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bench/lib/bench_options.hpp"
#include "bench/lib/stage_bench.hpp"

namespace binpick::bench {

// The runner `option` names: "auto" = opencv_ppf3d next to this executable if it exists, "off"
// = none, else a path. Empty path when there is none; why says why.
std::filesystem::path find_opencv_runner(const std::string& option, std::string* why);

// Runs both on the crops at every ratio of options.ref_ratios; files under OUT/opencv/.
// binpick_train_ms is the training time measured by the caller.
OpenCvComparison compare_with_opencv(const PpfModel& model, const BenchOptions& options,
                                     const std::vector<BenchCrop>& crops,
                                     const eval::Dataset& dataset, double binpick_train_ms);

}  // namespace binpick::bench
