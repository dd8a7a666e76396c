// Every parameter of detection with its default: the paper's values where it has one
// (docs/parameters.md). Each is described once, in the parameter table (param_table.cpp), from
// which the command line, the --params file, validation and the docs' table all come. Ratios are
// fractions of the model's diameter.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "host/detect/params/bin_spec.hpp"

namespace binpick {

struct DetectParams {
  // Hypotheses: which highest points are tried.
  std::uint32_t hypotheses = 5;
  std::uint32_t more_hypotheses = 5;
  double confident = 0.7;
  bool highest_up = false;
  double flat_region = 1.25;
  double exclusion_ratio = 1.2;
  std::uint32_t instances = 0;
  // The highest points sought taken in order of a coarse vote (prerank.hpp).
  bool prerank = true;
  double prerank_ref_ratio = 0.02;
  // A robot's mode: the hypotheses one at a time, until a confident pose or the budget.
  bool stop_at_confident = false;
  double budget_ms = 0;
  // Region: where hypotheses and crops may be.
  std::string roi;
  std::string bin = "auto";
  std::string bin_pose;  // a bin pose file (bin_pose_file.hpp): the bin given; "": --bin
  double bin_margin = 0.1;
  bool through_walls = false;
  bool over_rim = false;
  // Scene: the neighbourhood voted on.
  double crop_ratio = 1.0;
  double normal_ratio = 0.08;
  double noise_voxel = 2.0;
  // Voting.
  double ref_ratio = 0.2;
  std::uint32_t peaks_per_ref = 3;
  double peak_ratio = 0.9;
  bool unique_votes = false;
  bool spread_votes = false;
  bool local_peaks = true;
  double bucket_cap = 0.0;
  // Clustering.
  double cluster_distance = 0.144;
  double cluster_angle = 20.0;
  std::uint32_t candidates = 4;
  // Refinement.
  std::uint32_t refine_iterations = 10;
  double plane_search = 0.15;
  // Verification: the score's factors (host/detect/verify/score.hpp).
  double verify_tolerance = 0.04;
  double verify_noise_factor = 3.5;
  double verify_through = 1.0;
  double verify_patch = 0.2;
  double verify_area = 0.0;
  double verify_ray = 0.01;
  double verify_lookalike_holes = 0.005;
  double verify_edge = 1.0;
  double verify_rival = 2.0;
  double verify_lookalike = 1.0;
  // Picks: where to grasp the detections (host/detect/pick/).
  bool picks = false;
  double pick_score = 0.1;
  std::string grasps;            // a grasps JSON file; "": the model's own
  std::string gripper = "auto";  // suction:..., parallel:..., a JSON file, or auto
  double approach_cone = 45.0;
  double pick_tolerance = 0.02;
};

// Whether detection plans picks: --picks, or a --grasps file or --gripper given.
inline bool picks_wanted(const DetectParams& p) {
  return p.picks || !p.grasps.empty() || p.gripper != "auto";
}

// The first parameter out of its range: its name (as in a --params file), its value and the
// range allowed ("(0, 1]"). The caller that knows where the value came from (an option, a
// file) names that in its message.
struct ParamProblem {
  std::string name;
  double value = 0;
  std::string range;
  std::string message;  // a text parameter's complaint ("'x': expected ..."); then no value/range
};
// bin: gets --bin's spec when it parses (a bin mesh is read once, here).
std::optional<ParamProblem> find_param_problem(const DetectParams& params, BinSpec* bin = nullptr);
// The complaint after the parameter's name: "V must be in RANGE", or a text parameter's message.
std::string describe(const ParamProblem& problem);
// InputError naming the parameter ("detection parameter ref-ratio ...") for a value out of range.
// Returns --bin's spec (BinSpec: parse_bin), parsed on the way.
BinSpec check(const DetectParams& params);

// Highest points sought in an image: hypotheses + more_hypotheses, or max(hypotheses,
// instances) with instances.
std::size_t hypotheses_sought(const DetectParams& params);

}  // namespace binpick
