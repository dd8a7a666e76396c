// Whether a part gets the verification's outline test (pose_fit_shared.h, RefineOptions::
// outline_ratio). A right pose's outline is a depth step down to what the part lies on, about as
// deep as the part is thick there; a thin sheet lying on another shows a step of one sheet
// thickness, which the test's tolerance cannot tell from a surface running on. Measured on flat
// stacks of the 1.5 mm built-in plate, the test turned right top-ranked poses down (7 -> 5 of 8
// images), while on the bracket, bolt, tee and shaft it raised them (56 -> 64 of 84 images with
// distractors in view, docs/pipeline.md). So the test runs only for parts whose thinnest extent
// is at least twice its tolerance.
#pragma once

#include "host/core/mesh.hpp"

namespace binpick {

// The points' extent along their principal axis of least spread (mm); 0 for fewer than 3 points.
double thinnest_extent(const PointCloud& model);

// tolerance_ratio when thinnest_extent(model) >= 2 * tolerance_ratio * diameter, else 0.
float outline_ratio_for(const PointCloud& model, double diameter, double tolerance_ratio);

}  // namespace binpick
