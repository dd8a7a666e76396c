#include "host/app/detect_options.hpp"

#include <CLI/CLI.hpp>
#include <set>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/detect/batch/detect_params_file.hpp"
#include "host/detect/detector.hpp"

namespace binpick::cli {
namespace {

std::uint32_t narrow(std::int64_t v, const char* option) {
  if (v < 0 || v > 1000000) throw InputError(fmt::format("{} {} is out of range", option, v));
  return static_cast<std::uint32_t>(v);
}

}  // namespace

void add_detect_cli_options(CLI::App* verb, DetectCliOptions& a, const std::string& what) {
  verb->add_option("--params", a.params_file,
                   "JSON file of " + what + " parameters (from `binpick tune`); options given "
                   "here win");
  auto& p = a.params;
  auto& o = a.options;
  // One option per parameter, named as in a --params file, its default shown in the help.
  const auto add = [&](const std::string& name, auto& value, const std::string& text) {
    o[name] = verb->add_option("--" + name, value, what + ": " + text)->capture_default_str();
  };
  add("ref-ratio", p.ref_ratio,
      "reference points / subsampled scene points, in (0, 1]");
  add("hypotheses", a.hypotheses,
      "highest points tried per image");
  add("more-hypotheses", a.more_hypotheses,
      "when no pose of the first --hypotheses scores --confident or more, this many more "
          "highest points are tried and all ranked together (a bin with other parts mixed in "
          "puts highest points on them), in [0, 1000]; 0: never");
  add("highest-up", a.highest_up,
      "1: with a bin found (--bin), the highest points are the highest along the bin's up "
          "direction (a tilted camera's nearest points lie on the bin's near side, not on top of "
          "the pile); 0: nearest the camera (the paper's)");
  add("through-walls", a.through_walls,
      "1: points the sensor sees through a wall of the bin found (between a wire-mesh "
          "basket's bars) may hold highest points and crops; 0: they are kept out, as the walls "
          "are");
  add("over-rim", a.over_rim,
      "1: what reaches into the bin found over its rim from outside (a robot arm over the "
          "rim) may hold highest points and crops; 0: it is kept out, as the rim is");
  add("flat-region", p.flat_region,
      "flat-region test: a highest point on a flat patch this many times larger than the "
          "part's widest flat region (a plate lying on the parts sought) is skipped and the "
          "next highest point taken, in [1, 100]; 0: off");
  add("confident", p.confident,
      "a verified score at which the first hypotheses suffice, in [0, 1]");
  add("exclusion-ratio", p.exclusion_ratio,
      "radius excluded around a highest point, fraction of the diameter");
  add("crop-ratio", p.crop_ratio,
      "radius of the neighbourhood voted on, fraction of the diameter");
  add("cluster-distance", p.cluster_distance,
      "pose clustering translation threshold, fraction of the diameter");
  add("cluster-angle", p.cluster_angle,
      "pose clustering rotation threshold, degrees");
  add("peaks-per-ref", a.peaks_per_ref,
      "accumulator peaks kept per reference point, in [1, 16]");
  add("peak-ratio", p.peak_ratio,
      "a peak needs this fraction of its reference point's best votes");
  add("normal-ratio", p.normal_ratio,
      "scene normals: radius of the neighbourhood fitted, fraction of the diameter");
  add("unique-votes", a.unique_votes,
      "1: scene pairs of a reference point with equal features vote once "
          "(a plane cannot outvote the part), 0: every pair votes");
  add("spread-votes", a.spread_votes,
      "1: every vote also goes to the neighbouring alpha bin its value lies "
          "nearer, 0: one bin");
  add("local-peaks", a.local_peaks,
      "1: accumulator peaks must be local maxima along alpha, so the peaks "
          "kept are different poses; 0: the best cells");
  add("bucket-cap", p.bucket_cap,
      "a feature key votes for at most this many model pairs per model point (the most "
          "common keys, such as a flat face's, keep that many evenly spaced), in [0, 10000]; "
          "0: every pair (Drost)");
  add("noise-voxel", p.noise_voxel,
      "noisy depth: the scene's subsampling voxels are up to this many times longer along the "
          "camera's axis than across (the noise is estimated in each image; the full factor "
          "from 0.6 voxels of noise on, linear from 0.45: 3 % of the diameter and more at the "
          "default voxel), so a surface thickened by noise keeps about a clean one's points, "
          "in [1, 4]; 1: cubic voxels, the model's");
  add("candidates", a.candidates,
      "best pose clusters per hypothesis refined and verified, in [1, 64]");
  add("plane-search", p.plane_search,
      "thin parts (sheet metal): each candidate pose is also searched for over the sheet's "
          "plane (shifts within this fraction of the diameter, turns through the whole turn) "
          "for the pose whose edges the sensor sees step down most, refined and verified beside "
          "it, in [0, 1]; 0: off");
  add("refine-iterations", a.refine_iterations,
      "ICP steps per candidate pose, in [0, 100] (0: verify the voted pose)");
  add("verify-noise-factor", p.verify_noise_factor,
      "the verification tolerance widens to this many times the depth "
          "noise seen in the best-fitting pose (at most 3x), in [0, 100]; 0: fixed");
  add("verify-tolerance", p.verify_tolerance,
      "depth agreement of a verified model point, fraction of the diameter");
  add("verify-patch", p.verify_patch,
      "patch test: the score is multiplied by the share of the model's patches (cells of "
          "this side, fraction of the diameter) whose residuals average out, in [0, 1]; 0: off");
  add("verify-ray", p.verify_ray,
      "ray test: a pose whose residuals along the viewing rays spread wider than the image's "
          "best pose's (significance-corrected) by more than this (fraction of the diameter) "
          "has its score multiplied by band / excess, in [0, 1]; 0: off");
  add("verify-through", p.verify_through,
      "see-through cost: each visible model point where the sensor sees past the part counts "
          "against the pose as much as this many agreeing points count for it (the score is "
          "multiplied by 1 - W * seen-through / support), in [0, 100]; 0: off");
  add("verify-twin", p.verify_twin,
      "twin test: a pose that the sensor sees through, on average over the points where a "
          "look-alike of the part (a plate turned over) has a hole, by more than this "
          "(fraction of the diameter, after two standard errors) has its score multiplied by "
          "band / excess, in [0, 1]; 0: off");
  add("verify-edge", p.verify_edge,
      "edge test, for thin parts (sheet metal): the score is multiplied by the depth the "
          "sensor sees the part's edges step down by (mean over points just beyond them, plus "
          "two standard errors) over this many verification tolerances, at most 1, in [0, 10]; "
          "0: off");
  add("verify-lookalike", p.verify_lookalike,
      "look-alike share: a pose's score s is multiplied by s / (s + w a), a the best score among "
          "the poses refined from the same candidate that lie at its place turned another way "
          "round (a plate turned over): a pose its look-alike ties with keeps half, in [0, 1]; "
          "0: off");
  add("verify-area", p.verify_area,
      "seen-area test: the score is multiplied by the area the pose shows the sensor (its "
          "visible model points weighted by how squarely they face the camera, missing depth "
          "counting half) over this many times the part's mean projected area, at most 1: a "
          "plate seen edge on or a part barely peeking out loses, in [0, 10]; 0: off (the default; "
          "0.8 where steep wrong poses win, e.g. on a robot arm in view: docs/pipeline.md)");
  add("verify-rival", p.verify_rival,
      "rival test: of two poses on the same measured points, the one whose squared residuals "
          "along the rays are larger by more than this many standard errors of the paired "
          "differences cannot outrank the other (its score is capped at the other's times the "
          "ratio of their mean squares), in [0, 100]; 0: off");
  add("roi", p.roi,
      "only this box may hold hypotheses and crops: camera:x0,y0,z0,x1,y1,z1 (camera frame, "
          "mm) or bin:x0,y0,z0,x1,y1,z1 (the bin's frame: origin at the floor's centre, z up, "
          "x along the longer side; needs --bin); default: everywhere");
  add("bin", p.bin,
      "the bin: none; auto (find its floor and rim in each depth image); W,D,H (find a bin "
          "of this interior size, mm). Its walls, rim and outside are kept out of hypotheses "
          "and crops");
  add("bin-margin", p.bin_margin,
      "how far the bin's walls and rim are kept out, fraction of the diameter, in [0, 10]");
  add("instances", a.instances,
      "detections per image: 0 = one per hypothesis (the paper's); N in [1, 1000] = the N best "
          "verified poses of different parts (for BOP's recall), from max(hypotheses, N) highest "
          "points and every candidate of each, score-0 poses left out");
}

DetectParams resolve(const DetectCliOptions& a) {
  DetectParams p = a.params;
  p.hypotheses = narrow(a.hypotheses, "--hypotheses");
  p.more_hypotheses = narrow(a.more_hypotheses, "--more-hypotheses");
  p.peaks_per_ref = narrow(a.peaks_per_ref, "--peaks-per-ref");
  p.candidates = narrow(a.candidates, "--candidates");
  p.highest_up = narrow(a.highest_up, "--highest-up");
  p.through_walls = narrow(a.through_walls, "--through-walls");
  p.over_rim = narrow(a.over_rim, "--over-rim");
  p.unique_votes = narrow(a.unique_votes, "--unique-votes");
  p.spread_votes = narrow(a.spread_votes, "--spread-votes");
  p.local_peaks = narrow(a.local_peaks, "--local-peaks");
  p.refine_iterations = narrow(a.refine_iterations, "--refine-iterations");
  p.instances = narrow(a.instances, "--instances");
  if (!a.params_file.empty()) {
    std::set<std::string> given;
    for (const auto& [name, option] : a.options)
      if (option->count() > 0) given.insert(name);
    apply_params_file(a.params_file, p, given);
  }
  // Named as the user gave it: the option, or the parameter of the --params file.
  if (const auto bad = find_param_problem(p)) {
    const auto option = a.options.find(bad->name);
    const bool from_file = !a.params_file.empty() &&
                           (option == a.options.end() || option->second->count() == 0);
    const std::string name =
        from_file ? fmt::format("{}: {}", a.params_file, bad->name) : "--" + bad->name;
    throw InputError(fmt::format("{} {}", name, describe(*bad)));
  }
  return p;
}

}  // namespace binpick::cli
