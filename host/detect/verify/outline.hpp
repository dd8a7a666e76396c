// Whether a part gets the verification's outline (pose_fit_shared.h, RefineOptions::
// outline_ratio; docs/detect/verify.md, "Outline"). A right pose's outline is a depth step down
// to what the part lies on, about as deep as the part is thick there; a thin sheet lying on
// another shows a step of one sheet thickness, which the outline's tolerance cannot tell from a
// surface running on: on flat stacks of plates the outline turned right poses down
// (docs/decisions/2026-11-24-outline-not-for-thin-parts.md). So the outline runs only for parts
// whose thinnest extent is at least twice its tolerance; the edge step (edge_step.hpp) takes its
// place on thin parts.
#pragma once

#include "host/core/mesh.hpp"

namespace binpick {

// The points' extent along their principal axis of least spread (mm); 0 for fewer than 3 points.
double thinnest_extent(const PointCloud& model);

// tolerance_ratio when thinnest_extent(model) >= 2 * tolerance_ratio * diameter, else 0.
float outline_ratio_for(const PointCloud& model, double diameter, double tolerance_ratio);

}  // namespace binpick
