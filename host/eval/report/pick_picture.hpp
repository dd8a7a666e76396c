// The picture of an image's first picks (docs/picks.md, "Evaluation"): each pick's gripper drawn
// at its planned grasp over the intensity image, green where the pick succeeds at the true poses,
// red where it fails.
#pragma once

#include <vector>

#include "host/eval/metrics/pick_success.hpp"
#include "host/eval/report/scene_pictures.hpp"

namespace binpick::eval {

// The crop of the image around the picks (a diameter and a half about each grasp point),
// magnified to about 640 pixels. Per pick: its detection's model points (pink, dim), the gripper's solids as outlines, the cup's
// footprint on the grasp plane filled, and an arrow down the approach to the grasp point, labelled
// with the detection's rank. hyps: the image's detections (for the picked one's points).
Canvas picks_picture(const SceneView& view, const std::vector<const PickOutcome*>& picks,
                     const std::vector<const HypothesisResult*>& hyps, const ModelSamples& models,
                     double diameter);

}  // namespace binpick::eval
