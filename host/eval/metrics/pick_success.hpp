// Pick success (docs/picks.md, "Evaluation"): whether the robot would take a part with each
// image's first pick (order 1 of each obj_id in OUT.picks.csv). It does when the pick's detection
// is right (eval's loose operating point), the cup at the planned grasp, moved along its approach
// to the true part (at most 5 % of the diameter), seals on it as train's grasps do (the same lip
// test, so symmetric parts need no special case; parallel jaws: evaluate_picks), and the gripper meets nothing at the true
// poses: no other part's surface deeper than 2 % of the diameter inside it, its own part only at
// the contact, and not the bin (from synth.json where the dataset has one).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "host/eval/metrics/eval_dataset.hpp"
#include "host/core/mesh.hpp"
#include "host/eval/metrics/evaluate.hpp"

namespace binpick::eval {

// A first pick as OUT.picks.csv states it.
struct PickRow {
  int scene_id = 0, im_id = 0, obj_id = 1, rank = 0;
  Eigen::Isometry3d grasp = Eigen::Isometry3d::Identity();  // camera frame
  double width = 0;                                         // the cup's or the jaws' opening, mm
  std::string gripper;                                      // --gripper's text
};

// The rows of OUT.picks.csv with order 1; InputError naming the file and line for a malformed one.
std::vector<PickRow> read_first_picks(const std::filesystem::path& path);

// The bin in the world frame of synth (interior floor centre at the origin, z up), if the
// dataset's synth.json states it.
std::optional<Eigen::Vector3d> synth_bin_interior(const std::filesystem::path& dataset_root);

struct PickOutcome {
  PickRow pick;             // the pick judged
  bool right = false;       // the detection is right (loose)
  bool on_grasp = false;    // the cup seals on the true part
  std::string collision;    // what the gripper meets at the true poses ("" nothing)
  bool success() const { return right && on_grasp && collision.empty(); }
  // "succeeds", or the first reason it fails ("on a wrong detection", "off the true grasp",
  // "hits part 3 (obj_id 1)").
  std::string verdict() const;
};

struct PickSummary {
  std::size_t images = 0;  // images of the dataset with ground truth
  std::size_t picked = 0;  // of them, images with a first pick
  std::size_t success = 0; // first picks that succeed
  std::vector<PickOutcome> firsts;
  // success / images: an image without a pick counts as a failure.
  double rate() const { return images ? double(success) / double(images) : 0.0; }
};

// Each part's surface in its model frame (unit normals): train's dense sample at its refinement
// voxel (16 points a voxel face), so the lip finds the surface wherever it lies.
using PartSurfaces = std::map<int, PointCloud>;
// A part's surface sampled so (diameter mm).
PointCloud sample_part_surface(const Mesh& mesh, double diameter);
// Samples models/obj_NNNNNN.ply of each obj_id; InputError naming a missing or bad model.
PartSurfaces sample_part_surfaces(const Dataset& dataset, const std::set<int>& obj_ids);

// InputError for a pick of a detection the results do not have, or of an obj_id without
// a surface. A parallel-jaw pick holds its part when the jaws, closing from the planned opening,
// meet it on two faces facing them (antipodal, within 45 degrees); they touch nothing on the way.
// right: where a detection is right (eval's loose operating point).
PickSummary evaluate_picks(const Dataset& dataset, const EvalSummary& summary,
                           const std::vector<PickRow>& picks, const PartSurfaces& surfaces,
                           const std::optional<Eigen::Vector3d>& bin_interior,
                           const OperatingPoint& right);

}  // namespace binpick::eval
