// The detection pipeline of one image (paper section III-B/C): scene preparation, the
// highest points, and per hypothesis its neighbourhood -> voxel subsampling -> reference points
// -> voting and peaks (ppf_vote) -> candidate poses (ppf_pose) -> clustering (pose_cluster); the
// best cluster of each hypothesis is its detection. Everything data-parallel is a kernel; the
// model's table is uploaded once per Detector.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "host/detect/hypotheses/hypotheses.hpp"
#include "host/detect/select/detection.hpp"
#include "host/detect/vote/ppf_vote.hpp"
#include "host/detect/cluster/pose_cluster.hpp"
#include "host/detect/refine/plane_search.hpp"
#include "host/detect/refine/pose_fit.hpp"
#include "host/detect/refine/pose_refine.hpp"
#include "host/detect/verify/lookalike_holes.hpp"
#include "host/detect/verify/verify_candidates.hpp"
#include "host/core/timing.hpp"
#include "host/core/mesh.hpp"
#include "host/train/ppf_model.hpp"
#include "host/detect/scene/depth_to_points.hpp"

namespace binpick {

struct BinFit;
class SharedScene;

// Every parameter of detection; the paper's values are the defaults (docs/parameters.md).
// Ratios are fractions of the model's diameter.
struct DetectParams {
  double ref_ratio = 0.2;          // reference points / subsampled scene points (2 %: fast)
  std::uint32_t hypotheses = 5;    // highest points tried
  // Beyond the paper: when no pose of those scores `confident` or more, this many more highest
  // points are tried, and all are ranked together (0: never). A bin full of parts with others
  // mixed in puts the highest points of the low-passed image on the larger parts; a pose
  // scoring 0.7 or more is seldom wrong (docs/pipeline.md, "More hypotheses").
  std::uint32_t more_hypotheses = 5;
  // Flat-region test (0: off; flat_region.hpp): a highest point on a flat patch this many times
  // larger than the part's widest flat region is skipped and the next one taken (an image's
  // hypotheses on other, flatter parts). Measured in docs/pipeline.md, step 3.
  // 1: with a bin found (--bin), "highest" is along the bin's up rather than nearest the camera
  // (the same for a camera looking straight down; for a tilted one the nearest points are on the
  // bin's near side). 0: nearest the camera, the paper's. Measured in docs/pipeline.md, step 2:
  // off, since keeping out what is seen through the walls (through_walls) did better.
  std::uint32_t highest_up = 0;
  // 1: points the sensor sees through a wall of the bin found (between a wire-mesh basket's bars)
  // may hold highest points and crops; 0: they are kept out, as the walls are (bin_region.hpp).
  std::uint32_t through_walls = 0;
  // 1: what reaches into the bin over its rim from outside (a robot arm over the rim: over the
  // rim and joined to what stands over it beyond a side of the rim seen, over_rim.hpp) may hold
  // highest points and crops; 0: it is kept out, as the rim is. Measured in docs/pipeline.md,
  // step 1.
  std::uint32_t over_rim = 0;
  double flat_region = 1.25;
  double confident = 0.7;
  double exclusion_ratio = 1.2;    // radius excluded around a highest point
  double crop_ratio = 1.0;         // radius of the neighbourhood voted on
  double cluster_distance = 0.144; // translation threshold of pose clustering
  double cluster_angle = 20.0;     // rotation threshold of pose clustering, degrees
  std::uint32_t peaks_per_ref = 3; // accumulator peaks per reference point
  double peak_ratio = 0.9;         // ... with at least this fraction of its best votes
  std::uint32_t unique_votes = 0;  // 1: equal scene pairs of a reference point vote once
  std::uint32_t spread_votes = 0;  // 1: each vote also goes to the nearer neighbouring alpha bin
  std::uint32_t local_peaks = 1;   // 1: peaks must be local maxima along alpha
  // A feature key votes for at most this many model pairs per model point (evenly spaced;
  // ppf_bucket_cap.hpp); 0: all of them (Drost). Off: measured in docs/parameters.md, it makes
  // flat parts vote faster but costs a few hypotheses.
  double bucket_cap = 0.0;
  double normal_ratio = 0.08;      // scene normals: radius of the plane fitted (fraction)
  // At depth noise of 0.6 voxels and more (estimated in each image, depth_noise.hpp), the
  // scene's voxels are up to this many times longer along the camera's axis (1: cubic, as the
  // model's). Measured in docs/parameters.md: twice as fast voting at 3 and 5 % noise, as many
  // right poses.
  double noise_voxel = 2.0;
  std::uint32_t candidates = 4;    // best pose clusters per hypothesis refined and verified
  // Thin parts (plane_search.hpp): each candidate is also searched for over the sheet's plane,
  // shifts within this fraction of the diameter and the whole turn (0: off). Measured in
  // docs/pipeline.md, step 9.
  double plane_search = 0.15;
  std::uint32_t refine_iterations = 10;  // ICP steps per candidate (0: verify the voted pose)
  double verify_tolerance = 0.04;  // depth agreement of a verified model point (fraction)
  double verify_noise_factor = 3.5;  // tolerance widens to this x the noise seen (0: fixed)
  double verify_patch = 0.2;       // patch test's cell side (fraction; 0: no patch test)
  // Ray test's dead band (fraction; 0: off, ray_spread.hpp): a spread along the rays wider than
  // the image's best pose's by more than this costs score. 0.01 d, the patch test's dead band
  // (a right pose's leftover error); measured in docs/pipeline.md, step 9.
  double verify_ray = 0.01;
  // See-through cost (0: off, pose_refine.hpp): each visible model point where the sensor sees
  // past the part counts against the pose as much as this many agreeing points count for it;
  // measured in docs/pipeline.md, step 9.
  double verify_through = 1.0;
  // Twin test's dead band (fraction; 0: off, lookalike_holes.hpp): a pose whose surface the sensor
  // sees through where a look-alike of it has a hole, by more than this on average, costs
  // score. Measured in docs/pipeline.md, step 9.
  double verify_twin = 0.005;
  // Edge test's scale (0: off; lookalike_holes.hpp, edge_step.hpp), for thin parts only: the score is
  // multiplied by the depth the sensor sees the part's edges step down by (an upper bound) over
  // this many verification tolerances, at most 1. Measured in docs/pipeline.md, step 9.
  double verify_edge = 1.0;
  // Seen-area test's scale (0: off; seen_area.hpp): the score is multiplied by the area the
  // pose shows the sensor over this many times the part's mean projected area, at most 1.
  // Off by default: measured in docs/pipeline.md, step 9, it costs as many right poses seen
  // obliquely as it gains where steep wrong poses (a robot arm's side face) win.
  double verify_area = 0.0;
  // Rival test's significance (standard errors; 0: off; rival.hpp): a pose that fits the
  // measured points it shares with another pose worse by more than this cannot outrank it.
  // Measured in docs/pipeline.md, step 9.
  double verify_rival = 2.0;
  // Look-alike share's weight (0: off; lookalike_share.hpp): a pose's score is multiplied by
  // s / (s + w a), a the best score of the same candidate's poses turned another way round at
  // its place. Measured in docs/pipeline.md, step 9.
  double verify_lookalike = 1.0;
  // Where hypotheses and crops may be (bin_spec.hpp, docs/cli.md): "" (anywhere),
  // "camera:x0,y0,z0,x1,y1,z1" or "bin:..." (mm).
  std::string roi;
  std::string bin = "auto";        // none, auto or the interior size "W,D,H" (mm)
  double bin_margin = 0.1;         // the bin's walls and rim are kept out by this (fraction)
  // 0: one detection per hypothesis, each its best candidate (the paper's). N > 0: the N best
  // verified poses of different parts (instance_select.hpp), from max(hypotheses, N) highest
  // points and every candidate of each; poses with score 0 are left out.
  std::uint32_t instances = 0;
};
// The first parameter out of its range: its name (as in a --params file, docs/cli.md), its value
// and the range allowed ("(0, 1]"). The caller that knows where the value came from (an option,
// a file) names that in its message.
struct ParamProblem {
  ParamProblem(std::string name_, double value_, std::string range_, std::string message_ = {})
      : name(std::move(name_)), value(value_), range(std::move(range_)),
        message(std::move(message_)) {}
  std::string name;
  double value = 0;
  std::string range;
  std::string message;  // a text parameter's complaint ("'x': expected ..."); then no value/range
};
std::optional<ParamProblem> find_param_problem(const DetectParams& params);

// Highest points sought in an image: hypotheses + more_hypotheses, or max(hypotheses,
// instances) with instances.
std::size_t hypotheses_sought(const DetectParams& params);
// The complaint after the parameter's name: "V must be in RANGE", or a text parameter's message.
std::string describe(const ParamProblem& problem);
// InputError naming the parameter ("detection parameter ref-ratio ...") for a value out of range.
void check(const DetectParams& params);

// Time per stage over the work done (ms), for the summary line and the benchmark.
struct DetectTimes {
  double prepare_ms = 0;  // scene preparation, highest points, crops, subsampling
  double vote_ms = 0;     // features, votes, peaks
  double cluster_ms = 0;  // poses, compatibility, grouping
  double refine_ms = 0;   // refinement and verification
  std::size_t hypotheses = 0;
  std::size_t bin_sought = 0, bin_found = 0;  // images a bin was looked for in, and found in
  StageTimings stages;    // every stage in order, for --verbose
  DetectTimes& operator+=(const DetectTimes& o);
  double total_ms() const { return prepare_ms + vote_ms + cluster_ms + refine_ms; }
};

class Detector {
 public:
  // Checks params; uploads the model's table to dev, where every stage of detection runs (the
  // process's shared device unless a caller, such as a test, picks another).
  Detector(const PpfModel& model, const DetectParams& params,
           ocl::Device& dev = ocl::Device::shared());

  const PpfModel& model() const { return model_; }
  // Seconds the constructor spent building the OpenCL programs of detection (0 if this process
  // had built them before): paid once, and kept out of every image's time.
  double program_build_seconds() const { return program_build_s_; }
  const DetectParams& params() const { return params_; }
  // The instance budget of the images detected from now on (DetectParams::instances): detect
  // --targets sets it per image. std::logic_error above 1000 (the targets' reader refuses that).
  void set_instances(std::uint32_t n);

  // A depth image (BOP: raw * depth_scale mm). Detections best first (verified score; ties:
  // votes, then height order); a hypothesis without any vote gives no detection. With
  // params.instances > 0, up to that many detections of different parts instead (see there). InputError for an image that
  // does not match the camera or has no valid pixel.
  // If neighbourhoods is given, each hypothesis' subsampled neighbourhood (what it voted on) is
  // appended to it in hypothesis order, for the benchmark (which hands the same crops to
  // another detector) and for pictures.
  // If shared is given, the image's preparation and bin fit are taken from it when another
  // model made them, and left there for the next (shared_scene.hpp): the detections are the same.
  std::vector<Detection> detect(const DepthImage& depth, const bp_camera& cam,
                                DetectTimes* times = nullptr,
                                std::vector<PointCloud>* neighbourhoods = nullptr,
                                SharedScene* shared = nullptr);

  // A point cloud in the camera frame (z along the viewing axis: "highest" = smallest z). Without
  // normals they are estimated (PCA within normal_ratio of the diameter, oriented to the camera).
  // InputError for NaN or infinite values or an empty cloud.
  std::vector<Detection> detect(const PointCloud& cloud, DetectTimes* times = nullptr);

  // Voting and clustering only, on a neighbourhood already subsampled at the model's voxel (as
  // detect() hands out): the most voted cluster, unrefined, score 0; counts as one hypothesis in
  // times. The benchmark varies the reference ratio on these fixed crops.
  Detection detect_subsampled(const PointCloud& subsampled, DetectTimes* times = nullptr);

  // Of the last detect() on a depth image: the hypotheses skipped before voting (their crop had
  // fewer than kMinCropPoints points with normals after subsampling; score 0, no pose, the
  // reason says why), in hypothesis order; and what --roi / --bin found (empty without them).
  const std::vector<Detection>& skipped() const { return skipped_; }
  const std::string& region_report() const { return region_report_; }
  static constexpr std::size_t kMinCropPoints = 10;

 private:
  // Reference points, votes, clusters of a subsampled neighbourhood with normals: the best
  // `candidates` clusters, most voted first.
  std::vector<PoseCluster> vote_and_cluster(const PointCloud& subsampled, Detection& d,
                                            DetectTimes& t);
  // Refines and verifies every hypothesis' candidates against a point image on the device
  // (one batch for all), keeps each hypothesis' best and ranks them. With a bin found, a pose
  // that sinks the part into its floor scores 0 (below_floor.hpp). sensor: the points are a
  // sensor's depth image. Not for a cloud seen through a virtual camera (scene_cloud.hpp),
  // whose empty pixels are only gaps between points and whose depths are the nearest point's
  // in a pixel, not the surface along the ray: the twin test (lookalike_holes.hpp), which weighs
  // millimetres of depth at a few hundred points, runs only on a sensor's image (measured: on
  // the shaft's cloud it turned a right pose end for end).
  // vote(from, to) votes on the hypotheses [from, to) and keeps them; rank() refines,
  // verifies and ranks all kept so far. The first `hypotheses` of the `found`, then, if no pose
  // scores `confident` or more, the rest as well, all ranked together. With `instances`, all
  // in one round.
  std::vector<Detection> in_rounds(std::size_t found,
                                   const std::function<void(std::size_t, std::size_t)>& vote,
                                   const std::function<std::vector<Detection>()>& rank) const;
  std::vector<Detection> refine_and_rank(std::vector<Detection> detections,
                                         const std::vector<std::vector<PoseCluster>>& candidates,
                                         const ocl::Buffer<float>& points, const bp_camera& cam,
                                         DetectTimes& t, bool sensor, const BinFit* bin = nullptr,
                                         PlaneSearchMemo* searched = nullptr,
                                         RefineMemo* refined = nullptr,
                                         const ocl::Buffer<float>* search_points = nullptr);

  ocl::Device& dev_;
  double program_build_s_ = 0;
  std::vector<Detection> skipped_;
  std::string region_report_;
  double image_noise_ = 0;  // mm, the depth image's noise (depth_noise.hpp), for the near gate
  // The "no bin found" warning is printed once per Detector, and only for a bin of a given size:
  // `auto` (the default) is content to find none (DetectTimes counts the images it found one in).
  bool warned_no_bin_ = false;
  const PpfModel& model_;
  DetectParams params_;
  DeviceModel device_model_;
  DeviceFitModel fit_model_;
  // The fit points followed by the look-alikes' probes and the edge probes (lookalike_holes.hpp);
  // empty without probes.
  DeviceFitModel probe_fit_model_;
  PlaneSearchModel plane_search_model_;  // thin parts with --plane-search only
  ProbeModel probes_;
  VerifyCandidatesOptions verify_options_;  // from params_
  FitGeometry fit_geometry_;
  float outline_ratio_ = 0;  // the verification's outline test, 0 for thin parts (outline.hpp)
  double thinnest_extent_ = 0;  // mm, the model's extent along its least-variance axis
  // The flat-region test (flat_region.hpp) on a crop's subsample about hypothesis h: the reason
  // to skip it, or empty. noise: the image's depth noise (mm), voxel_factor: the scene voxels'
  // stretch along the camera's axis.
  std::string flat_skip_reason(const PointCloud& sample, const Hypothesis& h, double noise,
                               double voxel_factor) const;
  // The model's widest flat region at a plane tolerance, by tolerance step (computed once each).
  mutable std::map<int, std::size_t> flat_model_regions_;
};

}  // namespace binpick
