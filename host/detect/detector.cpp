#include "host/detect/detector.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/detect/ppf_pose.hpp"
#include "host/detect/scene_cloud.hpp"
#include "host/detect/scene_crop.hpp"
#include "host/detect/scene_neighbourhood.hpp"
#include "host/detect/scene_prepare.hpp"
#include "host/train/voxel_subsample.hpp"

namespace binpick {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw InputError(message);
}

bool in(double v, double lo, double hi) { return std::isfinite(v) && v >= lo && v <= hi; }

double sum_ms(const StageTimings& t, std::size_t from) {
  double ms = 0;
  for (std::size_t i = from; i < t.size(); ++i) ms += t[i].ms;
  return ms;
}

}  // namespace

std::optional<ParamProblem> find_param_problem(const DetectParams& p) {
  const std::pair<bool, ParamProblem> rules[] = {
      {in(p.ref_ratio, 0, 1) && p.ref_ratio > 0, {"ref-ratio", p.ref_ratio, "(0, 1]"}},
      {p.hypotheses >= 1 && p.hypotheses <= 1000, {"hypotheses", double(p.hypotheses), "[1, 1000]"}},
      {in(p.exclusion_ratio, 0, 100), {"exclusion-ratio", p.exclusion_ratio, "[0, 100]"}},
      {in(p.crop_ratio, 0, 100) && p.crop_ratio > 0, {"crop-ratio", p.crop_ratio, "(0, 100]"}},
      {in(p.cluster_distance, 0, 100), {"cluster-distance", p.cluster_distance, "[0, 100]"}},
      {in(p.cluster_angle, 0, 180), {"cluster-angle", p.cluster_angle, "[0, 180] degrees"}},
      {p.peaks_per_ref >= 1 && p.peaks_per_ref <= 16, {"peaks-per-ref", double(p.peaks_per_ref), "[1, 16]"}},
      {in(p.peak_ratio, 0, 1), {"peak-ratio", p.peak_ratio, "[0, 1]"}},
      {in(p.normal_ratio, 0, 10) && p.normal_ratio > 0, {"normal-ratio", p.normal_ratio, "(0, 10]"}},
  };
  for (const auto& [ok, problem] : rules)
    if (!ok) return problem;
  return std::nullopt;
}

void check(const DetectParams& p) {
  if (const auto bad = find_param_problem(p))
    throw InputError(fmt::format("detection parameter {} {} must be in {}", bad->name, bad->value,
                                 bad->range));
}

DetectTimes& DetectTimes::operator+=(const DetectTimes& o) {
  prepare_ms += o.prepare_ms;
  vote_ms += o.vote_ms;
  cluster_ms += o.cluster_ms;
  hypotheses += o.hypotheses;
  stages.insert(stages.end(), o.stages.begin(), o.stages.end());
  return *this;
}

Detector::Detector(const PpfModel& model, const DetectParams& params, ocl::Device& dev)
    : dev_(dev), model_(model), params_(params) {
  check(params_);
  require(model.diameter > 0 && model.voxel_size > 0 && !model.cloud.points.empty(),
          "the PPF model is empty");
  program_build_s_ = dev_.prebuild({"depth_to_points.cl", "scene_lowpass.cl", "scene_normals.cl",
                                    "hypotheses.cl", "scene_crop.cl", "voxel_subsample.cl",
                                    "device_scan.cl", "ppf_vote.cl", "pose_cluster.cl"});
  device_model_ = upload_model(dev_, model_);
}

Detection Detector::detect_neighbourhood(const PointCloud& neighbourhood, DetectTimes* times) {
  DetectTimes t;
  Stopwatch clock;
  Detection d;
  d.neighbourhood = neighbourhood.points.size();
  // The scene is subsampled like the model (its voxel), so that densities, and so votes, match.
  const VoxelSubsample sub = voxel_subsample(dev_, neighbourhood, model_.voxel_size);
  const double ms = clock.lap();
  t.prepare_ms += ms;
  t.stages.push_back({"subsample", ms});
  vote_and_cluster(sub.cloud, d, t);
  if (times) *times += t;
  return d;
}

void Detector::vote_and_cluster(const PointCloud& subsampled, Detection& d, DetectTimes& t) {
  auto& dev = dev_;
  Stopwatch clock;
  const std::vector<std::uint32_t> refs =
      select_reference_points(subsampled.points.size(), params_.ref_ratio);
  d.subsampled = subsampled.points.size();
  d.refs = refs.size();

  VoteOptions vo;
  vo.peaks_per_ref = params_.peaks_per_ref;
  vo.peak_ratio = float(params_.peak_ratio);
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
  const std::vector<PoseCluster> clusters = cluster_poses(dev, poses, co, &t.stages);
  t.cluster_ms += t.stages[t.stages.size() - 2].ms + t.stages.back().ms;
  d.clusters = clusters.size();
  if (!clusters.empty()) {
    d.R = clusters.front().q.toRotationMatrix();
    d.t = clusters.front().t;
    d.votes = clusters.front().votes;
  }
}

std::vector<Detection> Detector::finish(std::vector<Detection> detections) const {
  std::erase_if(detections, [](const Detection& d) { return d.votes == 0; });
  std::stable_sort(detections.begin(), detections.end(),
                   [](const Detection& a, const Detection& b) { return a.votes > b.votes; });
  return detections;
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

std::vector<Detection> Detector::detect(const DepthImage& depth, const bp_camera& cam,
                                        DetectTimes* times,
                                        std::vector<PointCloud>* neighbourhoods) {
  DetectTimes t;
  Stopwatch clock;
  require(depth.width > 0 && depth.height > 0, "the depth image is empty");
  require(std::any_of(depth.raw.begin(), depth.raw.end(), [](std::uint16_t v) { return v > 0; }),
          "the depth image has no valid pixel (all zero)");
  ScenePrepOptions prep;
  prep.normals.max_distance = float(params_.normal_ratio * model_.diameter);
  prep.read_back = false;
  prep.normals_everywhere = false;  // only where the neighbourhoods need them, below
  const PreparedScene scene = prepare_scene(dev_, depth, cam, prep);
  t.stages.insert(t.stages.end(), scene.timings.begin(), scene.timings.end());
  HypothesisOptions ho;
  ho.count = params_.hypotheses;
  ho.exclusion_radius = float(params_.exclusion_ratio * model_.diameter);
  const std::vector<Hypothesis> hyps = find_hypotheses(scene, ho, &t.stages);
  t.prepare_ms += clock.lap();

  std::vector<Detection> detections;
  for (std::size_t k = 0; k < hyps.size(); ++k) {
    CropOptions crop;
    crop.centre = hyps[k].point;
    crop.radius = float(params_.crop_ratio * model_.diameter);
    // Equal to voxel_subsample(crop_sphere(...)) on a scene with normals everywhere.
    const NeighbourhoodSample sample =
        sample_neighbourhood(scene, crop, prep.normals, model_.voxel_size, &t.stages);
    t.prepare_ms += clock.lap();
    Detection d;
    d.neighbourhood = sample.cropped;
    vote_and_cluster(sample.cloud, d, t);
    clock.lap();
    if (neighbourhoods) neighbourhoods->push_back(sample.cloud);
    d.hypothesis = hyps[k];
    d.index = static_cast<std::uint32_t>(k);
    detections.push_back(d);
  }
  t.hypotheses += hyps.size();
  if (times) *times += t;
  return finish(std::move(detections));
}

std::vector<Detection> Detector::detect(const PointCloud& input, DetectTimes* times) {
  DetectTimes t;
  Stopwatch clock;
  check_cloud(input);
  require(!input.points.empty(), "the point cloud is empty");
  PointCloud cloud = input;
  if (cloud.normals.empty()) cloud.normals = cloud_normals(cloud, float(0.1 * model_.diameter));
  CloudHypothesisOptions ho;
  ho.hypotheses.count = params_.hypotheses;
  ho.hypotheses.exclusion_radius = float(params_.exclusion_ratio * model_.diameter);
  const std::vector<Hypothesis> hyps = find_hypotheses(cloud, ho);
  const double prep_ms = clock.lap();
  t.prepare_ms += prep_ms;
  t.stages.push_back({"cloud hypotheses", prep_ms});

  std::vector<Detection> detections;
  for (std::size_t k = 0; k < hyps.size(); ++k) {
    CropOptions crop;
    crop.centre = hyps[k].point;
    crop.radius = float(params_.crop_ratio * model_.diameter);
    const PointCloud neighbourhood = crop_sphere(cloud, crop);
    const double crop_ms = clock.lap();
    t.prepare_ms += crop_ms;
    t.stages.push_back({"crop", crop_ms});
    Detection d = detect_neighbourhood(neighbourhood, &t);
    clock.lap();
    d.hypothesis = hyps[k];
    d.index = static_cast<std::uint32_t>(k);
    detections.push_back(d);
  }
  t.hypotheses += hyps.size();
  if (times) *times += t;
  return finish(std::move(detections));
}

}  // namespace binpick
