#include "host/detect/pick/plan_picks.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <fmt/format.h>

#include "host/core/angles.hpp"
#include "host/detect/pick/pick_clearance.hpp"

namespace binpick {
namespace {

// Clearance and height each add up to this to a pick's value, so they only order picks whose
// scores are within 0.04; at 0.1 they put a less sure pick first more often than they helped
// (docs/decisions/2026-12-07-pick-order.md).
constexpr double kOrderWeight = 0.02;

}  // namespace

std::vector<PlannedPick> plan_picks(ocl::Device& dev, const ocl::Buffer<float>& points,
                                    const bp_camera& cam, const std::vector<Detection>& detections,
                                    const std::vector<Grasp>& grasps, const Gripper& gripper,
                                    const BinFit* bin, const PickOptions& o) {
  std::vector<PlannedPick> picks(detections.size());
  const bool bin_known = bin && bin->found;
  // Down: into the bin, or along the camera's view.
  const Eigen::Vector3d down = bin_known ? Eigen::Vector3d(-bin->axes.col(2).normalized())
                                         : Eigen::Vector3d::UnitZ();
  const double cone_cos = std::cos(o.approach_cone * kDeg);
  const double cap = std::max(1e-3, 0.25 * o.part_diameter);

  struct Tried {
    std::size_t detection, grasp;
    Eigen::Isometry3d pose;
    double approach_cos;
  };
  std::vector<Tried> tried;
  std::vector<bp_pick_candidate> candidates;
  std::vector<std::size_t> outside_cone(detections.size(), 0), hits_bin(detections.size(), 0),
      of_kind(detections.size(), 0);
  std::vector<std::string> bin_part(detections.size());
  for (std::size_t i = 0; i < detections.size(); ++i) {
    const Detection& d = detections[i];
    if (!(d.score() >= o.min_score)) {
      picks[i].reason = fmt::format("score {:.2f} below --pick-score {:.2f}", d.score(), o.min_score);
      continue;
    }
    Eigen::Isometry3d part = Eigen::Isometry3d::Identity();
    part.linear() = d.R;
    part.translation() = d.t;
    for (std::size_t g = 0; g < grasps.size(); ++g) {
      if (grasps[g].kind != gripper.kind) continue;
      ++of_kind[i];
      const Eigen::Isometry3d pose = part * grasps[g].frame();
      const double c = pose.linear().col(2).dot(down);
      if (c < cone_cos) {
        ++outside_cone[i];
        continue;
      }
      const std::vector<GripperSolid> solids = gripper.solids(grasps[g]);
      if (bin_known) {
        const std::string hit =
            bin_contact(solids, pose, bin->axes, bin->origin, bin->interior, o.bin_tolerance);
        if (!hit.empty()) {
          ++hits_bin[i];
          bin_part[i] = hit;
          continue;
        }
      }
      tried.push_back({i, g, pose, c});
      candidates.push_back(pick_candidate(solids, pose, cam, float(o.tolerance), float(cap)));
    }
  }
  const std::vector<bp_pick_result> results = pick_clearance(dev, points, cam, candidates);

  std::vector<std::size_t> colliding(detections.size(), 0), least(detections.size(), SIZE_MAX);
  for (std::size_t k = 0; k < tried.size(); ++k) {
    const Tried& t = tried[k];
    PlannedPick& p = picks[t.detection];
    if (results[k].colliding > o.max_colliding) {
      ++colliding[t.detection];
      least[t.detection] = std::min<std::size_t>(least[t.detection], results[k].colliding);
      continue;
    }
    const double clearance = results[k].clearance;
    // The clearest grasp, then the one nearest straight down; the first of equals.
    if (!p.picked || clearance > p.clearance + 1e-6 ||
        (std::abs(clearance - p.clearance) <= 1e-6 &&
         t.approach_cos > p.pose.linear().col(2).dot(down) + 1e-9)) {
      p.picked = true;
      p.grasp = t.grasp;
      p.pose = t.pose;
      p.clearance = clearance;
      p.width = grasps[t.grasp].size;
    }
  }
  // Why the others have no pick.
  for (std::size_t i = 0; i < detections.size(); ++i) {
    PlannedPick& p = picks[i];
    if (p.picked || !p.reason.empty()) continue;
    if (of_kind[i] == 0)
      p.reason = fmt::format("no {} grasp", gripper.kind == Grasp::Kind::suction ? "suction" : "parallel");
    else if (outside_cone[i] == of_kind[i])
      p.reason = fmt::format("every grasp's approach is more than {:g} degrees from down", o.approach_cone);
    else
      p.reason = fmt::format(
          "{} grasps outside the approach cone, {} hit {}, {} collide with what the camera sees{}",
          outside_cone[i], hits_bin[i], bin_part[i].empty() ? "the bin" : bin_part[i], colliding[i],
          colliding[i] ? fmt::format(" (the least: {} points inside the gripper)", least[i]) : "");
  }
  // The order: score, then up to kOrderWeight each for clearance and height (docs).
  double top = -1e30, bottom = 1e30;
  for (const PlannedPick& p : picks)
    if (p.picked) {
      const double h = -p.pose.translation().dot(down);
      top = std::max(top, h);
      bottom = std::min(bottom, h);
    }
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < picks.size(); ++i) {
    PlannedPick& p = picks[i];
    if (!p.picked) continue;
    const double h = -p.pose.translation().dot(down);
    const double height = top > bottom ? (h - bottom) / (top - bottom) : 1.0;
    p.value = detections[i].score() + kOrderWeight * (p.clearance / cap) + kOrderWeight * height;
    order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return picks[a].value > picks[b].value; });
  for (std::size_t k = 0; k < order.size(); ++k) picks[order[k]].order = std::uint32_t(k + 1);
  return picks;
}

}  // namespace binpick
