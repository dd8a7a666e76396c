#include "host/detect/verify/verify_candidates.hpp"

#include <cmath>

#include "host/detect/verify/below_floor.hpp"
#include "host/detect/verify/lookalike_share.hpp"
#include "host/detect/verify/rival.hpp"

namespace binpick {

std::vector<VerifiedPose> verify_candidates(const VerifyScene& scene, const VerifyModel& model,
                                            const VerifyCandidatesOptions& opt,
                                            const std::vector<PoseToRefine>& poses,
                                            const std::vector<std::size_t>& group,
                                            RefineMemo* memo) {
  const FitGeometry& g = model.geometry;
  VerifyOptions vo = opt.verify;
  // What lies on the part is kept out of its fit near the end (depth images: the noise known).
  vo.refine.near_gate = scene.sensor;
  vo.refine.noise = scene.noise;
  // The rival needs the measured points on the pixels' rays: a sensor's image.
  const bool rival_on = scene.sensor && opt.rival_significance > 0;
  vo.keep_measured = rival_on;

  // Refinement, then phase 1 and the fit pass's factors.
  std::vector<VerifiedPose> out = refine_and_verify(scene.fit_sums, scene.cam, g,
                                                    model.fit_points, poses, vo, memo);
  // Phase 2: the probe pass's factors, on a sensor's image only: a cloud seen through a virtual
  // camera has no depth along the rays fine enough to weigh millimetres at a few hundred probes
  // (docs/decisions/2026-11-25-lookalike-holes.md).
  if (scene.sensor && scene.probe_sums && !model.probes.probes.points.empty()) {
    LookalikeHolesOptions ho;
    ho.band_ratio = opt.holes_band;
    ho.edge_scale = opt.edge_scale;
    ho.near_gate = vo.refine.near_gate;
    ho.noise = vo.refine.noise;
    lookalike_holes(scene.probe_sums, scene.cam, g, model.probes, out, ho);
  }
  // Phase 2: a physical check against the bin.
  if (scene.floor) mark_below_floor(out, model.cloud, g.diameter, scene.floor->up, scene.floor->d);
  // Phase 3: the rival cap, against the scores so far.
  if (rival_on) {
    RivalOptions ro;
    ro.significance = opt.rival_significance;
    ro.max_centre_distance = kRivalCentreRatio * g.diameter;
    // An RMS difference of 0.005 d, look-alike holes' band: a noise-free right pose's leftover
    // error is of that size, the model's sampling fitting one pose a little better than another
    // (docs/decisions/2026-11-25-rival.md).
    ro.dead_band_floor = std::pow(kRivalFloorRatio * g.diameter, 2);
    // A thin part's neighbours beyond its outline are sheets of itself a thickness lower, which
    // any pose shifted over them explains as well as the right one does its own surface: there
    // the edge step judges the outline, and only the shared points are compared.
    ro.count_unexplained = vo.outline_ratio > 0;
    cap_by_rivals(out, g.points, g.normals, model.spacing, scene.cam, g.centroid, ro);
  }
  // Phase 3: the look-alike share, against the fits after the cap.
  LookalikeOptions lo;
  lo.weight = opt.lookalike_weight;
  lo.max_distance = kLookalikeRatio * g.diameter;
  lookalike_share(out, group, g.centroid, lo);
  return out;
}

}  // namespace binpick
