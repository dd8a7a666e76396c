// The look-alike holes factor of verification: is the pose the part, or one of its look-alikes?
// (docs/detect/verify.md, "Look-alike holes"; host/train/lookalike_probes.hpp says what a probe
// is.)
//
// A plate turned over lies on the same outline and faces as the right pose: every other score
// term agrees with both. Only where one of the two has material and the other a hole does the
// depth image tell them apart, and there only by the depth of what lies behind the hole, often
// the plate beneath, one sheet thickness deeper: less than any tolerance, far less than the
// sensor's noise at one pixel. So the test averages: at a pose P, the probes of a look-alike S
// are the points of P's surface where P S has a hole. If P is right, the sensor sees surface
// there (depth excess about 0); if P S is right, it sees through P's surface (a positive
// excess: the sheet beneath, or beyond the gate). Per look-alike, the mean excess along the
// rays, less two standard errors, is the pose's evidence against it; the largest over its
// look-alikes, past a dead band, multiplies its score by band / excess (as the ray spread).
//
// A hole often shows no depth at all: a structured-light sensor's projector cannot light the
// bottom of a hole its camera looks into. So a probe without depth that faces the camera
// (within 60 degrees: obliquely seen surfaces, a shaft's flanks, often give no depth on real
// material) counts as seen through, and
// the share m of the pose's own visible points without depth (shadows, grazing, range: what the
// sensor misses on real surface there) is taken off the mean in the same units: a right pose
// in a shadow is not blamed for it, a pose over holes that give no depth is. The probes of a
// look-alike lie together, in a hole or two of the part, and a sensor that loses depth in
// patches (shiny sheet metal; docs/sensor_model.md) loses them together: their share without
// depth is one draw of m, not one per probe. So the spread of that one draw, sqrt(m (1 - m))
// gates, joins the standard error: a right pose whose look-alike's probes lie in one patch of
// lost depth is not blamed for it; with m near 0 (a paper bin) the term vanishes
// (docs/decisions/2026-12-02-lookalike-holes-patchy-depth.md). But where the sensor lost about
// half the pose's own points, the spread alone (a gate) outweighs any mean and the factor never
// fires, though a flip's probes with depth see through the holes by the whole gate. So the
// probes with depth are also taken alone (no depth saying nothing, as in the edge step): their
// mean less two standard errors, with at least min_probes of them, is evidence too, and the
// pose's excess against the look-alike is the larger of the two
// (docs/decisions/2026-12-02-lookalike-holes-probes-with-depth.md). With no probe missing the
// two are the same; a right pose's probes with depth lie on its surface.
// Probes where something lies in front (nearer than the gate), facing away or hidden say
// nothing. The excess of a probe is clamped to the gate (the verification tolerance), and one
// beyond it on the far side counts as the gate: one probe over an empty bin does not outweigh a
// hundred on the sheet beneath.
//
// The same pass carries the edge probes of a thin part (edge_probes.hpp, edge_step.hpp): points
// just beyond its edges, where a right pose's sensor sees the surface step down.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "host/core/mesh.hpp"
#include "host/detect/refine/pose_refine.hpp"
#include "host/detect/verify/verified_pose.hpp"

namespace binpick {

// A look-alike's evidence at one pose: the mean (mm) and its standard error over n probes, of
// which `missing` had no depth.
struct ProbeEvidence {
  double mean = 0, standard_error = 0;
  std::size_t n = 0, missing = 0;
};

// How a probe that faces the camera but has no depth counts.
enum class NoDepth {
  seen_through,  // as the gate (look-alike holes: a hole's bottom the projector cannot light)
  neutral,       // not at all, only in `missing` (the edge step)
};

// The evidence about look-alike `which` from a probe pass (pose_fit_shared.h: one residual,
// NaN where a probe gives no ICP term, and one class per probe) at pose (R, t): each probe's
// depth excess along its ray, clamped to [-gate, gate]; seen through without a term counts as
// gate, no depth as `no_depth` says; hidden, and in front without a term, are skipped. Probes
// of other look-alikes are skipped.
ProbeEvidence probe_evidence(std::span<const float> residuals, std::span<const std::uint8_t> classes,
                           const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                           const PointCloud& probes, std::span<const std::uint32_t> probe_lookalike,
                           std::uint32_t which, double gate,
                           NoDepth no_depth = NoDepth::seen_through);

// max(0, mean - m gate - 2 sqrt(standard error^2 + m (1 - m) gate^2)): m (missing_rate) is the
// share of the pose's visible points without depth. 0 with fewer than min_probes probes
// (untested).
double holes_excess(const ProbeEvidence& e, std::size_t min_probes, double missing_rate, double gate);

// max(0, mean - 2 standard errors) of a look-alike's probes with depth (probe_evidence with
// NoDepth::neutral); 0 with fewer than min_probes of them (untested). A pose's excess against a
// look-alike is the larger of this and holes_excess.
double seen_excess(const ProbeEvidence& with_depth, std::size_t min_probes);

// The probes on the device side: the fit points followed by the probes, so that the probe pass's
// z-buffer holds the whole model (a probe behind the part's own near side is hidden). The
// probes are the look-alikes' (probe_lookalike < lookalikes) followed by `edge_probes` edge
// probes (probe_lookalike == lookalikes).
struct ProbeModel {
  std::uint32_t fit_points = 0;  // residuals [0, fit_points) belong to the fit points
  PointCloud probes;             // model frame
  std::vector<std::uint32_t> probe_lookalike;
  std::uint32_t lookalikes = 0;  // look-alike count
  std::uint32_t edge_probes = 0;
};

struct LookalikeHolesOptions {
  float band_ratio = 0;          // the factor's dead band, fraction of the diameter; 0: no test
  float edge_scale = 0;          // edge step's scale, in tolerances (edge_step.hpp); 0: off
  std::size_t min_probes = 10;   // fewer visible probes with depth: untested
  bool near_gate = false;        // the probe pass's near gate (RefineOptions::near_gate)
  float noise = 0;               // mm, the image's depth noise, for it
};

// One probe pass (sums: pose_fit_sums on fit points + probes, or the reference) for every pose
// with a positive score, at its verification tolerance as the gate; sets the look-alike holes
// and edge step factors and their evidence (lookalike_excess / lookalike_tested, edge_step /
// edge_tested). No-op without probes or with both off.
void lookalike_holes(const FitSumsFn& sums, const bp_camera& cam, const FitGeometry& geometry,
                     const ProbeModel& model, std::vector<VerifiedPose>& poses,
                     const LookalikeHolesOptions& opt);

}  // namespace binpick
