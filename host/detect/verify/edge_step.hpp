// The edge step of verification, for thin parts (docs/detect/verify.md, "Edge step"; the points
// it reads are host/train/edge_probes.hpp's, measured in the look-alike holes' probe pass,
// lookalike_holes.hpp).
//
// A sheet lying on a sheet steps down at its edges by one thickness, less than the
// verification's tolerance, so the outline is off for thin parts (outline.hpp), and
// a pose shifted in its plane or turned on a stack of sheets agrees with the depth image
// everywhere but at its edges, where the sensor sees the sheet run on. Beyond a right pose's
// edges the sensor sees a step down: at least the part's thickness, often much more (a part
// it lies across, the floor), or no depth (the projector's shadow at an edge). So at every
// face probe with depth (edge_probes.hpp: not the rim probes, which see a step on any face seen
// obliquely) the depth excess along the ray is taken as the look-alike holes take it (clamped to the
// tolerance; something in front says nothing), and the mean plus two standard errors is how
// far the pose's edges are seen to step down at most. The score is multiplied by that step
// over `scale` tolerances, at most 1: a pose whose edges show no step keeps little, one whose
// edges drop by a tolerance keeps all.
//
// No depth beyond an edge says nothing (NoDepth::neutral): a sensor that loses depth in patches
// (shiny sheet metal) loses it beyond some edges and not others, and counted as a step, it let
// the pose whose edges lay in the patches win
// (docs/decisions/2026-11-25-edge-step-no-depth-neutral.md). Figures:
// docs/decisions/2026-11-25-edge-step.md.
#pragma once

#include "host/detect/verify/lookalike_holes.hpp"

namespace binpick {

// max(0, mean + 2 standard errors) of the edge probes' evidence (mm).
double edge_step(const ProbeEvidence& e);

// min(1, step / (scale x gate)); 1 for scale <= 0 or gate <= 0 (off).
double edge_factor(double step, double scale, double gate);

}  // namespace binpick
