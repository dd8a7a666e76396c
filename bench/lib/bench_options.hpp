// What `binpick bench` measures and on what: the paper's scene (1600 x 900, 350 parts
// of a built-in part), detection at 20 % and 2 % reference points, and the side-by-side run of
// OpenCV's PPF3DDetector when its runner was built. --quick is the smoke-test size.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "host/detect/detector.hpp"
#include "host/train/ppf_model.hpp"
#include "host/train/model_store.hpp"

namespace binpick::bench {

struct BenchOptions {
  PartSpec part{"builtin:bracket", {}};
  std::filesystem::path out = "binpick-bench";  // report, scenes, crops
  // Scenes measured. Two: a 350-part bin of the built-in bracket is minutes of physics (made
  // once, reused by a rerun); 10 hypotheses per reference ratio.
  int bins = 2;
  int objects = 350;
  std::uint32_t width = 1600, height = 900;
  std::uint64_t seed = 1;
  // The same bins at the size of the real sensor binpick is judged with: a
  // structured-light camera of real_width x real_height pixels, real_camera_height_mm away and
  // tilted by real_camera_tilt_deg, detected at the defaults (20 % reference points). 0 x 0:
  // not measured.
  std::uint32_t real_width = 2064, real_height = 1544;
  double real_camera_height_mm = 2000, real_camera_tilt_deg = 20;
  int repeats = 3;                             // timed runs per measurement; medians reported
  std::vector<double> ref_ratios{0.2, 0.02};   // the paper's two operating points
  PpfTrainParams train;                        // the paper's model
  DetectParams detect;                         // ref_ratio is taken from ref_ratios
  // Scaling sweeps.
  std::vector<double> scaling_ref_ratios{0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0};
  std::vector<double> scaling_crop_fractions{0.4, 0.55, 0.7, 0.85, 1.0};  // of the crop radius
  std::vector<double> scaling_voxel_ratios{0.035, 0.05, 0.07, 0.1};       // model resolution
  // "auto": the opencv_ppf3d runner next to the binpick executable if it was built; "off"; or
  // a path to the runner.
  std::string opencv = "auto";
  bool quick_peaks = false;
};

// The --quick preset: one small bin, one repetition, short sweeps; seconds, for the smoke test.
BenchOptions quick_options(BenchOptions base);

// InputError naming the option for values out of range.
void check(const BenchOptions& options);

}  // namespace binpick::bench
