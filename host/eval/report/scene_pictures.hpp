// The report's pictures of one image (the paper's Figures 3, 5 and 6): depth in false colour,
// the intensity image, the hypothesis neighbourhoods on the scene, the detections drawn over it,
// and a close-up of the top-ranked detection (model points in the scene cloud, two viewpoints).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "host/eval/metrics/evaluate.hpp"
#include "host/eval/report/raster.hpp"
#include "host/eval/report/scene_view.hpp"

namespace binpick::eval {

// Points sampled evenly on each object's model (models/obj_NNNNNN.ply), keyed by obj_id.
using ModelSamples = std::map<int, std::vector<Eigen::Vector3f>>;
ModelSamples sample_models(const Dataset& dataset, std::size_t points_per_model = 3000);

struct DepthRange {
  double near_mm = 0, far_mm = 0;
};

// near = dark, far = bright along viridis, from the 1st to the 99th percentile of valid depths;
// no data = black. range receives the mapped range if given.
Canvas depth_false_colour(const SceneView& view, DepthRange* range = nullptr);

// The intensity image (or, without one, the depth shaded grey) as a canvas.
Canvas intensity_picture(const SceneView& view, double brightness = 1.0);

// Scene pixels within `radius` mm of each hypothesis's translation, coloured by rank over the
// dimmed intensity image, with the rank (1 = first row) at each centre.
Canvas hypotheses_picture(const SceneView& view, const std::vector<const HypothesisResult*>& hyps,
                          double radius);

// Model points at each hypothesis's pose projected over the intensity image: green if correct
// at `at`, red otherwise; the top-ranked one ringed in gold; ranks labelled.
Canvas detections_picture(const SceneView& view, const std::vector<const HypothesisResult*>& hyps,
                          const ModelSamples& models, double diameter, const OperatingPoint& at);

// Figure 3: scene points (blue) near the top-ranked detection and the model at its pose (pink),
// seen from the camera and from 60 degrees aside, side by side. Nothing if hyps has no top.
Canvas closeup_picture(const SceneView& view, const std::vector<const HypothesisResult*>& hyps,
                       const ModelSamples& models, double diameter);

}  // namespace binpick::eval
