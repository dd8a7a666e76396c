// Refinement and verification of one image's candidate poses: the one place where the score's
// phases run, in their order (score.hpp; docs/detect/verify.md, "The score").
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "host/core/mesh.hpp"
#include "host/detect/refine/pose_fit.hpp"
#include "host/detect/refine/pose_refine.hpp"
#include "host/detect/verify/lookalike_holes.hpp"
#include "host/detect/verify/verified_pose.hpp"
#include "host/detect/verify/verify_poses.hpp"

namespace binpick {

// The bin's floor, up . p + d = 0 (up: unit, towards the camera).
struct Floor {
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  double d = 0;
};

// What verification reads of the image.
struct VerifyScene {
  FitSumsFn fit_sums;    // the fit model's pass against the image
  FitSumsFn probe_sums;  // the fit points followed by the probes (ProbeModel); empty: none
  bp_camera cam{};
  // A sensor's depth image: its measured points lie on the pixels' rays (the rival, the near
  // gate and the probe pass need that); false for a cloud seen through a virtual camera.
  bool sensor = false;
  float noise = 0;             // mm, the image's depth noise (depth_noise.hpp), for the near gate
  std::optional<Floor> floor;  // where a bin was found
};

// What it reads of the model.
struct VerifyModel {
  const FitGeometry& geometry;
  std::uint32_t fit_points = 0;  // the fit model's points (the minimum support's unit)
  const ProbeModel& probes;      // look-alike and edge probes (may be empty)
  const PointCloud& cloud;       // the model's points (below the floor)
  float spacing = 0;             // mm, the fit points' spacing (the rival's surfaces)
};

struct VerifyCandidatesOptions {
  // Refinement and the first pass; its near gate, noise and measured points are set from the
  // scene.
  VerifyOptions verify;
  float holes_band = 0;          // look-alike holes' dead band, fraction of the diameter; 0: off
  float edge_scale = 0;          // edge step's scale, in tolerances; 0: off
  double rival_significance = 0; // standard errors (rival.hpp); 0: off
  double lookalike_weight = 0;   // look-alike share's weight; 0: off
};

// Refines the poses (memo: refine_poses), then verifies them in the score's order: phase 1 and
// the fit pass's factors (verify_poses), the probe pass's factors (look-alike holes, edge step;
// sensors only), below the floor, then the rival cap (sensors only) and the look-alike share
// among the poses of one group (group[i]: the candidate pose i comes from).
std::vector<VerifiedPose> verify_candidates(const VerifyScene& scene, const VerifyModel& model,
                                            const VerifyCandidatesOptions& opt,
                                            const std::vector<PoseToRefine>& poses,
                                            const std::vector<std::size_t>& group,
                                            RefineMemo* memo = nullptr);

}  // namespace binpick
