#include "host/detect/params/param_table.hpp"

#include <cmath>

#include <fmt/format.h>

namespace binpick {
namespace {

using P = DetectParams;

constexpr ParamRange unit_open{0, 1, true};      // (0, 1]
constexpr ParamRange unit_closed{0, 1};          // [0, 1]

const ParamInfo kTable[] = {
    // Hypotheses.
    {"hypotheses", &P::hypotheses, {1, 1000}, "hypotheses",
     "highest points of the low-pass filtered image tried per image"},
    {"more-hypotheses", &P::more_hypotheses, {0, 1000}, "hypotheses",
     "when no pose of the first hypotheses scores --confident or more, this many more highest "
     "points are tried and all are ranked together (a bin with other parts mixed in puts "
     "highest points on them); 0: never"},
    {"confident", &P::confident, unit_closed, "hypotheses",
     "a verified score (its fit, before the look-alike share) at which the first hypotheses "
     "suffice"},
    {"highest-up", &P::highest_up, {}, "hypotheses",
     "with a bin found, the highest points are the highest along the bin's up (a tilted "
     "camera's nearest points lie on the bin's near side); off: nearest the camera, the paper's"},
    {"flat-region", &P::flat_region, {1, 100, false, true}, "hypotheses",
     "a highest point on a flat patch this many times larger than the part's widest flat region "
     "(a plate lying on the parts sought) is skipped and the next one taken; 0: off"},
    {"exclusion-ratio", &P::exclusion_ratio, {0, 100}, "hypotheses",
     "radius excluded around a highest point when the next is sought"},
    {"instances", &P::instances, {0, 1000}, "hypotheses",
     "detections per image: 0 = one per hypothesis (the paper's); N = the N best verified poses "
     "of different parts (for BOP's recall), from max(hypotheses, N) highest points and every "
     "candidate of each, poses scoring 0 left out"},
    {"prerank", &P::prerank, {}, "hypotheses",
     "the highest points sought (--hypotheses + --more-hypotheses) are each voted on coarsely "
     "(--prerank-ref-ratio) and taken in order of their best pose's votes, most first (a highest "
     "point on another part or the clutter gathers few); off: in height order, the paper's"},
    {"prerank-ref-ratio", &P::prerank_ref_ratio, unit_open, "hypotheses",
     "reference points / subsampled scene points of the coarse vote that ranks the highest "
     "points (--prerank)"},
    {"stop-at-confident", &P::stop_at_confident, {}, "hypotheses",
     "a robot's mode: the hypotheses are refined and verified one at a time in their order, "
     "and detection stops at the first whose pose's fit scores --confident or more (the time to "
     "it is reported); off: the first --hypotheses together, the rest only if none is confident"},
    {"budget-ms", &P::budget_ms, {0, 1e6}, "hypotheses",
     "a robot's time budget per image, ms of detection: the hypotheses are refined and verified "
     "one at a time in their order until it is spent (the one under way is finished); 0: none"},
    // Region.
    {"roi", &P::roi, {}, "region",
     "only this box may hold hypotheses and crops: camera:x0,y0,z0,x1,y1,z1 (camera frame, mm) "
     "or bin:x0,y0,z0,x1,y1,z1 (the bin's frame: origin at the floor's centre, z up, x along "
     "the longer side; needs --bin); empty: everywhere"},
    {"bin", &P::bin, {}, "region",
     "the bin: none; auto (find its floor and rim in each depth image); W,D,H (find a bin of "
     "this interior size, mm); mesh:FILE (of its model's interior: synth --bin-mesh's frame). "
     "Its walls, rim and outside are kept out of hypotheses and crops"},
    {"bin-pose", &P::bin_pose, {}, "region",
     "a fixed cell's bin, given: a JSON file of its pose in the camera frame and its interior "
     "(docs/formats.md), used in every image instead of --bin; empty: --bin"},
    {"bin-margin", &P::bin_margin, {0, 10}, "region",
     "how far the bin's walls and rim are kept out"},
    {"through-walls", &P::through_walls, {}, "region",
     "points the sensor sees through a wall of the bin found (between a wire-mesh basket's bars) "
     "may hold highest points and crops; off: they are kept out, as the walls are"},
    {"over-rim", &P::over_rim, {}, "region",
     "what reaches into the bin found over its rim from outside (a robot arm) may hold highest "
     "points and crops; off: it is kept out, as the rim is"},
    // Scene.
    {"crop-ratio", &P::crop_ratio, {0, 100, true}, "scene",
     "radius of the neighbourhood voted on about a highest point"},
    {"normal-ratio", &P::normal_ratio, {0, 10, true}, "scene",
     "scene normals: radius of the neighbourhood a plane is fitted to"},
    {"noise-voxel", &P::noise_voxel, {1, 4}, "scene",
     "noisy depth: the scene's subsampling voxels are up to this many times longer along the "
     "camera's axis than across (from 0.6 voxels of noise estimated in the image, linear from "
     "0.45), so a surface thickened by noise keeps about a clean one's points; 1: cubic, the "
     "model's"},
    // Voting.
    {"ref-ratio", &P::ref_ratio, unit_open, "voting",
     "reference points / subsampled scene points (0.02: the paper's fast setting)"},
    {"peaks-per-ref", &P::peaks_per_ref, {1, 16}, "voting",
     "accumulator peaks kept per reference point"},
    {"peak-ratio", &P::peak_ratio, unit_closed, "voting",
     "a peak needs this fraction of its reference point's best votes"},
    {"unique-votes", &P::unique_votes, {}, "voting",
     "scene pairs of a reference point with equal features vote once (a plane cannot outvote "
     "the part); off: every pair votes"},
    {"spread-votes", &P::spread_votes, {}, "voting",
     "every vote also goes to the neighbouring alpha bin its value lies nearer; off: one bin"},
    {"local-peaks", &P::local_peaks, {}, "voting",
     "accumulator peaks must be local maxima along alpha, so the peaks kept are different "
     "poses; off: the best cells"},
    {"bucket-cap", &P::bucket_cap, {0, 10000}, "voting",
     "a feature key votes for at most this many model pairs per model point (the commonest "
     "keys, a flat face's, keep that many evenly spaced); 0: every pair (Drost)"},
    // Clustering.
    {"cluster-distance", &P::cluster_distance, {0, 100}, "clustering",
     "pose clustering's translation threshold"},
    {"cluster-angle", &P::cluster_angle, {0, 180, false, false, "degrees"}, "clustering",
     "pose clustering's rotation threshold"},
    {"candidates", &P::candidates, {1, 64}, "clustering",
     "best pose clusters per hypothesis refined and verified"},
    // Refinement.
    {"refine-iterations", &P::refine_iterations, {0, 100}, "refinement",
     "ICP steps per candidate pose; 0: verify the voted pose"},
    {"plane-search", &P::plane_search, unit_closed, "refinement",
     "thin parts: each candidate is also searched for over the sheet's plane (shifts within "
     "this, the whole turn) for the pose whose edges step down most, refined and verified "
     "beside it; 0: off"},
    // Verification.
    {"verify-tolerance", &P::verify_tolerance, {1e-4, 1}, "verification",
     "agreement: depth tolerance of a model point that agrees"},
    {"verify-noise-factor", &P::verify_noise_factor, {0, 100}, "verification",
     "the tolerance widens to this many times the depth noise the best-fitting pose shows (at "
     "most 3 times); 0: fixed"},
    {"verify-through", &P::verify_through, {0, 100}, "verification",
     "see-through: each visible model point where the sensor sees past the part counts against "
     "the pose as much as this many agreeing points count for it; 0: off"},
    {"verify-patch", &P::verify_patch, unit_closed, "verification",
     "patch bias: the score is multiplied by the share of the model's patches (cells of this "
     "side) whose residuals average out; 0: off"},
    {"verify-area", &P::verify_area, {0, 10}, "verification",
     "seen area: the score is multiplied by the area the pose shows the sensor over this many "
     "times the part's mean projected area, at most 1 (a plate seen edge on loses); 0: off"},
    {"verify-ray", &P::verify_ray, unit_closed, "verification",
     "ray spread: a pose whose residuals along the rays spread wider than the image's best "
     "pose's by more than this has its score multiplied by band / excess; 0: off"},
    {"verify-lookalike-holes", &P::verify_lookalike_holes, unit_closed, "verification",
     "look-alike holes: a pose the sensor sees through, where a look-alike of the part (a plate "
     "turned over) has a hole, by more than this on average has its score multiplied by band / "
     "excess; 0: off",
     "verify-twin"},
    {"verify-edge", &P::verify_edge, {0, 10}, "verification",
     "edge step, thin parts: the score is multiplied by the step down the sensor sees at the "
     "part's edges over this many tolerances, at most 1; 0: off"},
    {"verify-rival", &P::verify_rival, {0, 100}, "verification",
     "rival: of two poses on the same measured points, the one fitting worse by more than this "
     "many standard errors cannot outrank the other; 0: off"},
    {"verify-lookalike", &P::verify_lookalike, unit_closed, "verification",
     "look-alike share: a pose's score s is multiplied by s / (s + w a), a the best score of the "
     "same candidate turned another way round at its place (a tie keeps half); 0: off"},
    // Picks.
    {"picks", &P::picks, {}, "picks",
     "plan a pick (also with --grasps or --gripper given) for every detection scoring "
     "--pick-score or more: its clearest grasp that the "
     "gripper reaches within --approach-cone without touching the bin or anything the camera "
     "sees; picks ordered by score, clearance and height (written to OUT.picks.csv)"},
    {"pick-score", &P::pick_score, unit_closed, "picks",
     "the verified score a detection needs to be picked (a robot's threshold: the score of a "
     "right pose drops with the sensor's noise, to 0.15 on a thin plate at 5 % noise, so this "
     "lies well below --confident; eval's calibrated threshold tells a cell's own)"},
    {"grasps", &P::grasps, {}, "picks",
     "a grasps JSON file (suction and parallel-jaw grasps in the model frame, docs/"
     "picks.md); empty: the model's own (train's, from its flat faces or its --grasps)"},
    {"gripper", &P::gripper, {}, "picks",
     "suction:CUP,STANDOFF,BODY_D,BODY_L or parallel:FINGER_W,FINGER_D,FINGER_L,PALM_H (mm), a "
     "gripper JSON file, or auto (a suction tool with the grasps' cup, a stand-off of a tenth of "
     "the diameter and a body as wide as the cup, two diameters long)"},
    {"approach-cone", &P::approach_cone, {0, 90}, "picks",
     "degrees a grasp's approach may lie from straight down into the bin (the camera's view "
     "axis without a bin)"},
    {"pick-tolerance", &P::pick_tolerance, {0, 1}, "picks",
     "a measured point deeper inside the gripper than this (or three times the image's depth "
     "noise, if more) is a collision"},
};

std::string number_text(double v) { return fmt::format("{}", v); }

}  // namespace

std::span<const ParamInfo> detect_param_table() { return kTable; }

const ParamInfo* find_param(const std::string& name) {
  for (const ParamInfo& p : kTable)
    if (name == p.name || (p.old_name && name == p.old_name)) return &p;
  return nullptr;
}

bool is_flag(const ParamInfo& p) { return std::holds_alternative<bool P::*>(p.member); }
bool is_text(const ParamInfo& p) { return std::holds_alternative<std::string P::*>(p.member); }
bool is_count(const ParamInfo& p) { return std::holds_alternative<std::uint32_t P::*>(p.member); }

std::string range_text(const ParamInfo& p) {
  if (is_flag(p)) return "on/off";
  if (is_text(p)) return "text";
  const ParamRange& r = p.range;
  std::string text = fmt::format("{}{}, {}]", r.lo_open ? "(" : "[", number_text(r.lo),
                                 number_text(r.hi));
  if (r.or_zero) text = "{0} or " + text;
  if (*r.unit) text += std::string(" ") + r.unit;
  return text;
}

double number_of(const ParamInfo& p, const DetectParams& params) {
  return std::visit(
      [&](auto member) -> double {
        using T = std::remove_cvref_t<decltype(params.*member)>;
        if constexpr (std::is_same_v<T, std::string>) return NAN;
        else return double(params.*member);
      },
      p.member);
}

std::string default_text(const ParamInfo& p) {
  const DetectParams defaults;
  if (is_text(p)) return defaults.*std::get<std::string P::*>(p.member);
  if (is_flag(p)) return defaults.*std::get<bool P::*>(p.member) ? "on" : "off";
  return number_text(number_of(p, defaults));
}

std::string param_table_markdown() {
  std::string out = "| parameter | default | range | group | what it does |\n";
  out += "| --- | --- | --- | --- | --- |\n";
  for (const ParamInfo& p : kTable) {
    const std::string name = is_flag(p) ? fmt::format("`--{0}` / `--no-{0}`", p.name)
                                        : fmt::format("`--{}`", p.name);
    const std::string value = default_text(p);
    const std::string shown = value.empty() ? (is_text(p) ? "(none)" : "") : fmt::format("`{}`", value);
    out += fmt::format("| {} | {} | {} | {} | {}{} |\n", name, shown, range_text(p), p.group,
                       p.help,
                       p.old_name ? fmt::format(" (`{}` in older --params files)", p.old_name)
                                  : std::string());
  }
  return out;
}

}  // namespace binpick
