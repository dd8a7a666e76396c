// BOP's VSD recall (eval_bop19_pose.py): the error of each considered estimate to each target
// instance of its image and obj_id at every tau (bop_vsd.hpp), matched and counted at every
// correctness threshold as MSSD and MSPD are (bop_matching.hpp); AR_VSD is the mean recall over
// the 10 taus x 10 thresholds. Rendering is cached as the toolkit caches it: per image, each
// estimate and each target is drawn once, in one pass, and only where the images of the two
// bounding spheres overlap (elsewhere the error is 1 without rendering, as in
// eval_calc_errors.py).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "host/eval/metrics/bop_matching.hpp"
#include "host/eval/metrics/bop_vsd.hpp"
#include "host/eval/metrics/eval_dataset.hpp"
#include "host/formats/bop/results_csv.hpp"

namespace binpick::eval {

// One (image, obj_id) as BOP scores it.
struct ScoredGroup {
  ImageKey image;
  int obj_id = 1;
  std::vector<const bop::ResultRow*> rows;  // the considered estimates, in matching order
  std::vector<int> targets;                 // its target instances (indices into image.gt)
};

struct VsdRecall {
  std::string unavailable;         // why VSD was not computed (no depth image); empty if it was
  double delta_mm = kBopVsdDelta;  // the visibility tolerance used
  std::vector<double> taus;        // fractions of the diameter
  std::vector<MetricRecall> by_tau;  // recall over bop_vsd_thresholds() at each tau
  double average = 0;              // AR_VSD: mean over taus and thresholds
  int renders = 0;                 // models drawn (estimates and targets, once per image)
  int pairs_compared = 0;          // (estimate, target) pairs whose sphere images overlap
  int pairs_skipped = 0;           // the others, error 1 without rendering
  double render_ms = 0, compare_ms = 0;  // wall clock of the renders and of the comparisons
};

// AR_VSD of the i-th obj_id (as listed in by_tau[k].objects): the mean of its recalls.
double object_vsd_average(const VsdRecall& vsd, std::size_t i);

// groups: every scored (image, obj_id) (rows may be empty), images of the dataset. models_dir:
// where obj_NNNNNN.ply of each obj_id is (models_eval/ or models/: the toolkit renders its eval
// models). Images' depth comes from their depth PNG (depth_scale of scene_camera.json); without
// one, with a model file without triangles, or without a Vulkan device, VSD is `unavailable`. InputError for a model or
// depth file that cannot be read.
VsdRecall bop_vsd_recall(const Dataset& dataset, const std::vector<ScoredGroup>& groups,
                         const std::filesystem::path& models_dir,
                         double delta_mm = kBopVsdDelta);

}  // namespace binpick::eval
