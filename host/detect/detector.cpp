#include "host/detect/detector.hpp"
#include "host/detect/detector_steps.hpp"

#include "host/detect/pick/plan_picks.hpp"
#include "host/formats/grasps/grasp_json.hpp"
#include "host/detect/verify/below_floor.hpp"
#include "host/detect/verify/seen_area.hpp"
#include "host/detect/hypotheses/flat_region.hpp"
#include "host/detect/hypotheses/prerank.hpp"
#include "host/detect/bin/bin_fit.hpp"
#include "host/detect/select/instance_select.hpp"
#include "host/detect/select/select_detections.hpp"
#include "host/detect/refine/candidate_poses.hpp"
#include "host/detect/verify/lookalike_share.hpp"
#include "host/detect/verify/outline.hpp"
#include "host/detect/scene/scene_lowpass.hpp"
#include "host/train/edge_probes.hpp"
#include "host/train/probe_surface.hpp"

#include <algorithm>
#include <optional>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <iostream>
#include <span>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/detect/bin/bin_region.hpp"
#include "host/detect/params/bin_pose_file.hpp"
#include "host/detect/params/bin_spec.hpp"
#include "host/detect/scene/cloud_image.hpp"
#include "host/detect/scene/depth_noise.hpp"
#include "host/detect/scene/image_memory.hpp"
#include "host/detect/vote/ppf_pose.hpp"
#include "host/detect/refine/pose_refine.hpp"
#include "host/detect/verify/rival.hpp"
#include "host/detect/hypotheses/scene_cloud.hpp"
#include "host/detect/scene/scene_crop.hpp"
#include "host/detect/scene/scene_neighbourhood.hpp"
#include "host/detect/scene/scene_prepare.hpp"
#include "host/detect/shared_scene.hpp"
#include "host/detect/refine/plane_search.hpp"
#include "host/train/ppf_bucket_cap.hpp"
#include "host/train/voxel_subsample.hpp"

namespace binpick {
namespace {

double sum_ms(const StageTimings& t, std::size_t from) {
  double ms = 0;
  for (std::size_t i = from; i < t.size(); ++i) ms += t[i].ms;
  return ms;
}

using detector_steps::crop_about;
using detector_steps::detection_for;
using detector_steps::require;

}  // namespace


std::vector<Detection> Detector::in_rounds(std::size_t found,
                                           const std::function<void(std::size_t, std::size_t)>& vote,
                                           const std::function<std::vector<Detection>()>& rank,
                                           const Stopwatch& started, DetectTimes& t) {
  rounds_report_.clear();
  // Confident when some pose fits that well, whether or not its look-alike fits as well
  // (lookalike_share.hpp): a part with a close look-alike would otherwise take the second round
  // on every image.
  bool confident = false;
  const auto ranked = [&](std::size_t voted) {
    std::vector<Detection> out = rank();
    if (!confident && std::any_of(out.begin(), out.end(), [&](const Detection& d) {
          return d.fit_score() >= params_.confident;
        })) {
      confident = true;
      t.first_confident_ms.push_back(started.elapsed());
      rounds_report_ = fmt::format("the first confident pose after {:.0f} ms ({} hypotheses)",
                                   t.first_confident_ms.back(), voted);
    }
    return out;
  };
  // (An instance budget, --targets', ranks every hypothesis' poses together.)
  const bool one_at_a_time =
      (params_.stop_at_confident || params_.budget_ms > 0) && params_.instances == 0;
  if (!one_at_a_time) {
    const std::size_t first =
        params_.instances > 0 ? found : std::min<std::size_t>(found, params_.hypotheses);
    vote(0, first);
    std::vector<Detection> out = ranked(first);
    if (first == found || confident) return out;
    // The second round's candidates are refined and ranked with the first's, as if all had been
    // tried at once: the rival cap compares poses of neighbouring hypotheses
    // (docs/decisions/2026-11-25-more-hypotheses.md).
    vote(first, found);
    return ranked(found);
  }
  // A robot's mode: each round refines and verifies one more hypothesis with those before it
  // (their ICP is kept: RefineMemo), so the ranking is always of all voted so far.
  std::vector<Detection> out;
  for (std::size_t voted = 0; voted < found;) {
    vote(voted, voted + 1);
    ++voted;
    out = ranked(voted);
    const auto stop = [&](const std::string& why) {
      rounds_report_ += fmt::format("{}stopped after {} of {} hypotheses: {}",
                                    rounds_report_.empty() ? "" : "; ", voted, found, why);
    };
    if (confident && params_.stop_at_confident) {
      stop("a confident pose (--stop-at-confident)");
      break;
    }
    if (params_.budget_ms > 0 && started.elapsed() >= params_.budget_ms && voted < found) {
      stop(fmt::format("the budget of {} ms spent ({:.0f} ms)", params_.budget_ms,
                       started.elapsed()));
      break;
    }
  }
  return out;
}

DetectTimes& DetectTimes::operator+=(const DetectTimes& o) {
  prepare_ms += o.prepare_ms;
  vote_ms += o.vote_ms;
  cluster_ms += o.cluster_ms;
  refine_ms += o.refine_ms;
  pick_ms += o.pick_ms;
  hypotheses += o.hypotheses;
  bin_sought += o.bin_sought;
  bin_found += o.bin_found;
  first_confident_ms.insert(first_confident_ms.end(), o.first_confident_ms.begin(),
                            o.first_confident_ms.end());
  stages.insert(stages.end(), o.stages.begin(), o.stages.end());
  return *this;
}

Detector::Detector(const PpfModel& model, const DetectParams& params, ocl::Device& dev)
    : dev_(dev), model_(model), params_(params) {
  const BinSpec bin = check(params_);
  bin_spec_ = params_.bin_pose.empty() ? bin : read_bin_pose(params_.bin_pose);
  require(model.diameter > 0 && model.voxel_size > 0 && !model.cloud.points.empty(),
          "the PPF model is empty");
  program_build_s_ = dev_.prebuild({"depth_to_points.cl", "scene_lowpass.cl", "scene_normals.cl",
                                    "hypotheses.cl", "scene_crop.cl", "voxel_subsample.cl",
                                    "device_scan.cl", "ppf_vote.cl", "pose_cluster.cl",
                                    "pose_fit.cl"});
  if (!params_.roi.empty() || bin_spec_.mode != BinSpec::Mode::none)
    program_build_s_ += dev_.prebuild({"scene_mask.cl", "bin_planes.cl"});
  if (picks_wanted(params_)) {
    grasps_ = params_.grasps.empty() ? model_.grasps : read_grasps_json(params_.grasps);
    if (params_.gripper != "auto") {
      gripper_ = parse_gripper(params_.gripper);
    } else {
      const auto cup = std::find_if(grasps_.begin(), grasps_.end(),
                                    [](const Grasp& g) { return g.kind == Grasp::Kind::suction; });
      gripper_ = default_suction_gripper(model_.diameter, cup != grasps_.end()
                                                              ? cup->size
                                                              : kDefaultCupRatio * model_.diameter);
    }
    program_build_s_ += dev_.prebuild({"pick_clearance.cl"});
  }
  device_model_ = upload_model(
      dev_, model_, bucket_cap_entries(params_.bucket_cap, model_.cloud.points.size()));
  // The denser refinement points where the model file has them (version 3 on).
  const PointCloud& fit_cloud = model_.fit_cloud.points.empty() ? model_.cloud : model_.fit_cloud;
  fit_model_ = upload_fit_model(dev_, fit_cloud);
  if (params_.verify_patch > 0)
    fit_geometry_.patches = model_patches(fit_cloud, float(params_.verify_patch * model_.diameter));
  if (params_.verify_ray > 0 || params_.verify_rival > 0 || params_.verify_area > 0) {
    fit_geometry_.points = fit_cloud.points;
    fit_geometry_.normals = fit_cloud.normals;
  }
  if (params_.verify_area > 0) fit_geometry_.mean_area = mean_projected_area(fit_cloud.normals);
  fit_geometry_.diameter = model_.diameter;
  fit_geometry_.voxel_size = model_.voxel_size;
  fit_geometry_.centroid = model_centroid(model_.cloud);
  outline_ratio_ = outline_ratio_for(model_.cloud, model_.diameter, params_.verify_tolerance);
  flat_skip_.emplace(model_.cloud, model_.diameter, model_.voxel_size, params_.flat_region,
                     outline_ratio_ == 0);
  thinnest_extent_ = thinnest_extent(model_.cloud);
  // The probes of one extra pass: the look-alikes' (look-alike holes), then, for a thin part (no
  // outline factor), the edge probes that continue its faces (edge step; edge_probes.hpp says
  // why not its rims').
  probes_.lookalikes = static_cast<std::uint32_t>(model_.lookalikes.size());
  if (params_.verify_lookalike_holes > 0) {
    probes_.probes = model_.lookalike_probes;
    probes_.probe_lookalike = model_.probe_lookalike;
  }
  if (params_.verify_edge > 0 && outline_ratio_ == 0) {
    const PointCloud faces = face_probes(model_.edge_probes, model_.edge_probe_rim);
    probes_.edge_probes = static_cast<std::uint32_t>(faces.points.size());
    append_cloud(probes_.probes, faces);
    probes_.probe_lookalike.resize(probes_.probes.points.size(), probes_.lookalikes);
  }
  if (params_.plane_search > 0 && outline_ratio_ == 0 && !model_.edge_probes.points.empty()) {
    plane_search_model_ = upload_plane_search_model(dev_, model_.edge_probes, model_.cloud,
                                                    fit_geometry_.centroid);
    program_build_s_ += dev_.prebuild({"plane_search.cl"});
  }
  if (!probes_.probes.points.empty()) {
    probes_.fit_points = fit_model_.size;
    PointCloud all = fit_cloud;
    append_cloud(all, probes_.probes);
    probe_fit_model_ = upload_fit_model(dev_, all);
  }
  // Refinement and verification, from the parameters (docs/detect/verify.md).
  VerifyOptions& vo = verify_options_.verify;
  vo.refine.iterations = params_.refine_iterations;
  vo.refine.tolerance_ratio = float(params_.verify_tolerance);
  vo.noise_factor = float(params_.verify_noise_factor);
  vo.outline_ratio = outline_ratio_;
  vo.ray_band_ratio = float(params_.verify_ray);
  vo.through_weight = float(params_.verify_through);
  vo.area_scale = float(params_.verify_area);
  verify_options_.holes_band = float(params_.verify_lookalike_holes);
  verify_options_.edge_scale = float(params_.verify_edge);
  verify_options_.rival_significance = params_.verify_rival;
  verify_options_.lookalike_weight = params_.verify_lookalike;
}

std::vector<PoseCluster> Detector::vote_and_cluster(const PointCloud& subsampled, Detection& d,
                                                    DetectTimes& t, double ref_ratio) {
  auto& dev = dev_;
  Stopwatch clock;
  const std::vector<std::uint32_t> refs = select_reference_points(
      subsampled.points.size(), ref_ratio > 0 ? ref_ratio : params_.ref_ratio);
  d.subsampled = subsampled.points.size();
  d.refs = refs.size();

  VoteOptions vo;
  vo.peaks_per_ref = params_.peaks_per_ref;
  vo.peak_ratio = float(params_.peak_ratio);
  vo.unique_votes = params_.unique_votes;
  vo.spread_alpha = params_.spread_votes;
  vo.local_max = params_.local_peaks;
  const std::size_t before = t.stages.size();
  const std::vector<VotePeak> peaks =
      vote_peaks(dev, device_model_, subsampled, refs, vo, &t.stages);
  d.peaks = peaks.size();
  t.vote_ms += sum_ms(t.stages, before);
  clock.lap();

  const std::vector<PoseCandidate> poses = poses_from_peaks(peaks, subsampled, refs, model_);
  t.stages.push_back({"poses", clock.lap()});
  ClusterOptions co;
  co.max_distance = float(params_.cluster_distance * model_.diameter);
  co.max_angle_deg = float(params_.cluster_angle);
  co.centre = fit_geometry_.centroid.cast<float>();
  // Poses equal up to a turn about the part's axis are one pose. Discrete symmetries stay out:
  // the candidates then become different poses instead of copies of the best, which cost strict
  // precision (docs/decisions/2026-11-24-cluster-discrete-symmetries.md).
  if (!model_.symmetries.continuous.empty()) co.symmetries = model_.symmetries;
  std::vector<PoseCluster> clusters = cluster_poses(dev, poses, co, &t.stages);
  t.cluster_ms += t.stages[t.stages.size() - 2].ms + t.stages.back().ms;
  d.clusters = clusters.size();
  if (clusters.size() > params_.candidates) clusters.resize(params_.candidates);
  if (!clusters.empty()) {
    d.R = clusters.front().q.toRotationMatrix();
    d.t = clusters.front().t;
    d.votes = clusters.front().votes;
  }
  return clusters;
}

std::vector<std::size_t> Detector::vote_order(
    std::size_t found, std::size_t ranked,
    const std::function<const HypothesisCrop&(std::size_t)>& crop, DetectTimes& t) {
  ranked = std::min(ranked, found);
  if (!params_.prerank || ranked < 2) return prerank_order({}, found);
  // The crops first: crop() times them as their own stages (preparation), the stage below is
  // the coarse votes alone.
  for (std::size_t k = 0; k < ranked; ++k) crop(k);
  Stopwatch clock;
  DetectTimes coarse;  // its stages are one line in --verbose
  std::vector<double> votes(ranked, -1.0);
  for (std::size_t k = 0; k < ranked; ++k) {
    const HypothesisCrop& c = crop(k);
    if (!c.reason.empty()) continue;
    const double n = double(c.cloud.points.size());
    Detection d;
    const std::vector<PoseCluster> clusters = vote_and_cluster(
        c.cloud, d, coarse, std::min(1.0, std::max(params_.prerank_ref_ratio, kPrerankRefs / n)));
    votes[k] = clusters.empty() ? 0.0 : double(clusters.front().votes) / double(d.refs);
  }
  const double ms = clock.lap();
  t.prepare_ms += ms;
  t.stages.push_back({fmt::format("prerank ({} highest points)", ranked), ms});
  return prerank_order(votes, found);
}

std::vector<Detection> Detector::refine_and_rank(
    std::vector<Detection> detections, const std::vector<std::vector<PoseCluster>>& candidates,
    const ocl::Buffer<float>& points, const bp_camera& cam, DetectTimes& t, bool sensor,
    const BinFit* bin, PlaneSearchMemo* searched_before, RefineMemo* refined_before,
    const ocl::Buffer<float>* search_points) {
  Stopwatch clock;
  // Thin parts on a depth image: each candidate's in-plane search (plane_search.hpp) adds the
  // pose found, if its edges step down more than the voted pose's. All candidates are searched
  // in one batch (one launch a stage), on the depth image the search reads.
  const bool search = sensor && plane_search_model_.probes > 0;
  std::vector<std::optional<Eigen::Isometry3d>> searched(0);
  if (search) {
    const std::vector<Eigen::Isometry3d> starts = cluster_poses_in_order(candidates);
    searched.resize(starts.size());
    if (!starts.empty()) {
      PlaneSearchMemo none;
      const std::vector<PlaneSearchResult> found = plane_search(
          searched_before ? *searched_before : none, dev_,
          point_depths(dev_, search_points ? *search_points : points, cam), cam,
          plane_search_model_, starts, params_.plane_search * model_.diameter,
          float(params_.verify_tolerance * model_.diameter));
      for (std::size_t i = 0; i < found.size(); ++i)
        if (found[i].score > found[i].start_score) searched[i] = found[i].pose;
    }
    const double ms = clock.lap();  // part of refinement in the summary
    t.refine_ms += ms;
    t.stages.push_back({"plane search", ms});
  }
  const CandidatePoses expanded = expand_candidates(candidates, model_.lookalikes, searched);

  VerifyScene scene;
  scene.fit_sums = [&](const std::vector<bp_pose_fit>& fits) {
    return pose_fit_sums(dev_, points, cam, fit_model_, fits);
  };
  if (!probes_.probes.points.empty())
    scene.probe_sums = [&](const std::vector<bp_pose_fit>& fits) {
      return pose_fit_sums(dev_, points, cam, probe_fit_model_, fits);
    };
  scene.cam = cam;
  scene.sensor = sensor;
  scene.noise = float(image_noise_);
  if (bin && bin->found) scene.floor = Floor{bin->axes.col(2), bin->floor_d()};
  const VerifyModel model{fit_geometry_, fit_model_.size, probes_, model_.cloud,
                          model_.voxel_size / kFitVoxelDivisor};
  const std::vector<VerifiedPose> verified = verify_candidates(
      scene, model, verify_options_, expanded.poses, expanded.group, refined_before);
  const double ms = clock.lap();
  t.refine_ms += ms;
  t.stages.push_back({"refine+verify", ms});
  // Every verified pose competes for the instance budget (instance_select.hpp); else each
  // hypothesis keeps its best.
  if (params_.instances > 0)
    return select_instances(every_pose(detections, verified, expanded.origin),
                            fit_geometry_.centroid, kDuplicateRatio * model_.diameter,
                            params_.instances);
  return best_per_hypothesis(std::move(detections), verified, expanded.origin);
}

Detection Detector::detect_subsampled(const PointCloud& subsampled, DetectTimes* times) {
  DetectTimes t;
  Detection d;
  d.neighbourhood = subsampled.points.size();
  vote_and_cluster(subsampled, d, t);
  t.hypotheses += 1;
  if (times) *times += t;
  return d;
}

void Detector::set_instances(std::uint32_t n) {
  if (n > 1000) throw std::logic_error("an instance budget above 1000");
  params_.instances = n;
}

RegionSetup Detector::region_setup(double noise) const {
  RegionSetup region;
  region.noise = noise;
  region.roi = parse_roi(params_.roi);
  region.bin = bin_spec_;
  region.margin = params_.bin_margin * model_.diameter;
  region.above = model_.diameter;
  region.min_height = 0.5 * model_.diameter;  // a tray shallower than half a part holds none
  region.min_side = model_.diameter;          // nor one narrower than a part
  region.floor_clearance_cap = 0.5 * thinnest_extent_;
  region.keep_through_walls = params_.through_walls;
  region.keep_over_rim = params_.over_rim;
  region.over_rim_gap = 0.25 * model_.diameter;  // a hole in the depth of an arm's face
  return region;
}

void Detector::note_region(const SceneRegionMask& masked, const RegionSetup& region,
                           DepthView depth, DetectTimes& t) {
  if (region.wanted()) {
    const std::size_t valid = std::size_t(std::count_if(
        depth.raw.begin(), depth.raw.end(), [](std::uint16_t v) { return v > 0; }));
    const bool mask = masked.mask.has_value();
    region_report_ = masked.report;
    region_report_ += fmt::format("{}mask: {} of {} pixels with depth may be used ({} excluded)",
                                  region_report_.empty() ? "" : "; ", mask ? masked.kept : valid,
                                  valid, mask ? valid - masked.kept : 0);
  }
  last_bin_ = masked.bin;
  if (masked.bin) {
    ++t.bin_sought;
    t.bin_found += masked.bin->found;
  }
  if (!masked.warning.empty() && !warned_no_bin_ && bin_spec_.mode != BinSpec::Mode::find) {
    std::cerr << "warning: " << masked.warning << "\n";
    warned_no_bin_ = true;
  }
}

std::vector<Detection> Detector::detect(DepthView depth, const bp_camera& cam,
                                        DetectTimes* times,
                                        std::vector<PointCloud>* neighbourhoods,
                                        SharedScene* shared) {
  DetectTimes t;
  Stopwatch clock;
  const Stopwatch started;
  require(depth.width > 0 && depth.height > 0, "the depth image is empty");
  check_image_fits_in_memory(depth.width, depth.height);
  require(std::any_of(depth.raw.begin(), depth.raw.end(), [](std::uint16_t v) { return v > 0; }),
          "the depth image has no valid pixel (all zero)");
  ScenePrepOptions prep;
  prep.normals.metric_radius = float(params_.normal_ratio * model_.diameter);
  prep.normals.max_distance = prep.normals.metric_radius;
  prep.normals.focal = 0.5f * (cam.fx + cam.fy);
  prep.read_back = false;
  prep.normals_everywhere = false;  // only where the neighbourhoods need them, below
  prep.lowpass = false;  // apply_region writes it, from the kept points when it masks
  skipped_.clear();
  region_report_.clear();
  PreparedScene scene = shared ? shared->scene_for_model(dev_, depth, cam, prep)
                               : prepare_scene(dev_, depth, cam, prep);
  t.stages.insert(t.stages.end(), scene.timings.begin(), scene.timings.end());
  // The image's depth noise: for the scene voxels (below), the bin fit's floor and ICP's near
  // gate (pose_refine.hpp).
  Stopwatch noise_clock;
  image_noise_ = depth_noise_mm(depth, cam);
  const double noise = params_.noise_voxel > 1 || bin_spec_.mode != BinSpec::Mode::none ? image_noise_ : 0.0;
  t.stages.push_back({"noise", noise_clock.lap()});
  // --roi / --bin: the mask of the pixels that may be used, and the low-pass of those only.
  const RegionSetup region = region_setup(noise);
  const BinFit* known_bin = shared ? shared->bin(bin_key(), model_.diameter) : nullptr;
  const SceneRegionMask masked =
      apply_region(scene, region, prep.lowpass_radius, &t.stages, known_bin);
  if (shared && masked.bin) shared->keep_bin(bin_key(), model_.diameter, *masked.bin);
  const ocl::Buffer<std::uint8_t>* mask = masked.mask ? &*masked.mask : nullptr;
  note_region(masked, region, depth, t);
  // Noisy depth: scene voxels longer along the camera's axis (depth_noise.hpp).
  const double voxel_factor = scene_voxel_factor(noise, model_.voxel_size, params_.noise_voxel);
  if (voxel_factor > 1)
    region_report_ +=
        fmt::format("{}depth noise {:.2f} mm ({:.2f} voxels): scene voxels {:.2f} times deeper",
                    region_report_.empty() ? "" : "; ", noise, noise / model_.voxel_size,
                    voxel_factor);
  HypothesisOptions ho;
  ho.count = hypotheses_sought(params_);
  ho.exclusion_radius = float(params_.exclusion_ratio * model_.diameter);
  if (params_.highest_up && masked.bin && masked.bin->found) {
    ho.up = masked.bin->axes.col(2).normalized().cast<float>();
    region_report_ +=
        fmt::format("{}highest along the bin's up", region_report_.empty() ? "" : "; ");
  }
  Stopwatch hyp_clock;
  const auto find = [&] {
    return find_hypotheses(dev_, scene.device->points, scene.device->filtered, scene.width,
                           scene.height, ho, mask, &cam);  // cam: rounds on the exclusion's rectangle
  };
  std::vector<Hypothesis> hyps = find();
  t.stages.push_back({"hypotheses", hyp_clock.lap()});
  // Highest points to stand in for those the flat-region test skips, found when needed: the
  // rounds again with as many more as were skipped (the same rounds give the same first ones),
  // at most twice those sought (docs/decisions/2026-12-02-flat-region.md).
  std::size_t flat_skipped = 0;
  const auto find_more = [&] {
    const std::size_t want = std::min(2 * hypotheses_sought(params_), hyps.size() + flat_skipped);
    if (hyps.size() < ho.count || want <= hyps.size()) return false;
    Stopwatch more_clock;
    ho.count = std::uint32_t(want);
    flat_skipped = 0;
    hyps = find();
    t.stages.push_back({"hypotheses", more_clock.lap()});
    return true;
  };
  t.prepare_ms += clock.lap();

  // Each highest point's crop, sampled once: the coarse ranking and the vote share it.
  std::vector<std::optional<HypothesisCrop>> crops;
  const auto crop = [&](std::size_t k) -> const HypothesisCrop& {
    if (crops.size() < hyps.size()) crops.resize(hyps.size());
    if (!crops[k]) {
      clock.lap();
      // Equal to voxel_subsample(crop_sphere(...)) on a scene with normals everywhere (with the
      // crop's z divided by the voxel factor for the grid: depth_stretch).
      NeighbourhoodSample sample =
          sample_neighbourhood(scene, crop_about(hyps[k], params_.crop_ratio * model_.diameter),
                               prep.normals, model_.voxel_size, &t.stages, mask,
                               float(voxel_factor));
      HypothesisCrop c;
      c.cloud = std::move(sample.cloud);
      c.cropped = sample.cropped;
      if (c.cloud.points.size() < kMinCropPoints) {
        // Nothing to vote on (a hole, a speck of depth, the edge of the region): said, not voted.
        c.reason = fmt::format(
            "skipped: the crop has {} points with depth, {} with a normal after subsampling "
            "(fewer than {})",
            c.cropped, c.cloud.points.size(), kMinCropPoints);
      } else {
        c.reason = flat_skip_->reason(c.cloud, hyps[k].point, noise, voxel_factor);
        c.flat = !c.reason.empty();
      }
      crops[k] = std::move(c);
      t.prepare_ms += clock.lap();
    }
    return *crops[k];
  };
  VoteQueue queue{vote_order(hyps.size(), hypotheses_sought(params_), crop, t)};
  queue.more = [&] {  // stand-ins beyond those ranked, in height order
    if (!find_more()) return false;
    for (std::size_t k = queue.order.size(); k < hyps.size(); ++k) queue.order.push_back(k);
    return true;
  };
  queue.flat_skipped = &flat_skipped;
  Voted voted;
  const auto vote = [&](std::size_t from, std::size_t to) {
    vote_from_queue(queue, from, to, crop, hyps, neighbourhoods, voted, clock, t);
  };
  // Noisy depth: the in-plane search reads the low-passed depth (plane_search.hpp).
  std::optional<ocl::Buffer<float>> search_points;
  if (plane_search_model_.probes > 0 && params_.plane_search > 0 &&
      search_reads_lowpass(noise, thinnest_extent_) && !hyps.empty()) {
    float farthest = 0;
    for (const Hypothesis& h : hyps) farthest = std::max(farthest, h.depth);
    const int radius =
        search_lowpass_radius(kEdgeMarginVoxels * model_.voxel_size / kProbeVoxelDivisor,
                              farthest / std::max(cam.fx, cam.fy));
    if (radius >= 1) {
      const std::size_t n = std::size_t(scene.width) * scene.height;
      ocl::Buffer<float> filtered(dev_, n);
      enqueue_lowpass_depth(dev_, scene.device->points, scene.width, scene.height, radius,
                            filtered);
      search_points.emplace(dev_, 4 * n);
      enqueue_lowpass_points(dev_, scene.device->points, filtered, n, *search_points);
      region_report_ += fmt::format(
          "{}depth noise {:.2f} mm, deeper than half the sheet ({:.2f} mm): the in-plane search "
          "reads the depth low-passed over {} x {} pixels",
          region_report_.empty() ? "" : "; ", noise, thinnest_extent_, 2 * radius + 1,
          2 * radius + 1);
    }
  }
  PlaneSearchMemo searched;  // the first round's searches and ICP, for the second
  RefineMemo refined;
  const auto rank = [&] {
    return refine_and_rank(voted.detections, voted.candidates, scene.device->points, cam, t,
                           true, masked.bin ? &*masked.bin : nullptr, &searched, &refined,
                           search_points ? &*search_points : nullptr);
  };
  std::vector<Detection> detections =
      in_rounds(std::min(hyps.size(), hypotheses_sought(params_)), vote, rank, started, t);
  add_picks(detections, scene.device->points, cam, masked.bin ? &*masked.bin : nullptr,
            image_noise_, t);
  if (times) *times += t;
  return detections;
}

void Detector::vote_from_queue(VoteQueue& queue, std::size_t from, std::size_t to,
                               const std::function<const HypothesisCrop&(std::size_t)>& crop,
                               const std::vector<Hypothesis>& hyps,
                               std::vector<PointCloud>* neighbourhoods, Voted& voted,
                               Stopwatch& clock, DetectTimes& t) {
  std::size_t taken = from;
  while (taken < to && (queue.next < queue.order.size() || (queue.more && queue.more()))) {
    const std::size_t k = queue.order[queue.next++];
    const HypothesisCrop& c = crop(k);
    Detection d = detection_for(hyps, k);
    d.neighbourhood = c.cropped;
    if (neighbourhoods) neighbourhoods->push_back(c.cloud);
    if (!c.reason.empty()) {
      d.subsampled = c.cloud.points.size();
      d.reason = c.reason;
      skipped_.push_back(d);
      if (!c.flat)
        ++taken;
      else if (queue.flat_skipped)
        ++*queue.flat_skipped;
      continue;
    }
    ++taken;
    clock.lap();
    voted.candidates.push_back(vote_and_cluster(c.cloud, d, t));
    clock.lap();
    voted.detections.push_back(d);
  }
  t.hypotheses += taken - from;
}

void Detector::add_picks(std::vector<Detection>& detections, const ocl::Buffer<float>& points,
                         const bp_camera& cam, const BinFit* bin, double noise, DetectTimes& t) {
  if (!gripper_) return;
  Stopwatch pick_clock;
  PickOptions po;
  po.min_score = params_.pick_score;
  po.approach_cone = params_.approach_cone;
  po.bin_tolerance = params_.pick_tolerance * model_.diameter;
  po.tolerance = std::max(po.bin_tolerance, 3 * noise);
  po.part_diameter = model_.diameter;
  const std::vector<PlannedPick> picks =
      plan_picks(dev_, points, cam, detections, grasps_, *gripper_, bin, po);
  for (std::size_t i = 0; i < detections.size(); ++i) detections[i].pick = picks[i];
  t.pick_ms += pick_clock.lap();
  t.stages.push_back({"picks", t.pick_ms});
}

}  // namespace binpick
