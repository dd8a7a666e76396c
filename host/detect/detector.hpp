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

#include "host/detect/bin/bin_fit.hpp"
#include "host/detect/bin/bin_region.hpp"
#include "host/detect/hypotheses/flat_region.hpp"
#include "host/detect/hypotheses/hypotheses.hpp"
#include "host/detect/hypotheses/prerank.hpp"
#include "host/detect/params/detect_params.hpp"
#include "host/detect/select/detection.hpp"
#include "host/detect/vote/ppf_vote.hpp"
#include "host/detect/cluster/pose_cluster.hpp"
#include "host/detect/refine/plane_search.hpp"
#include "host/detect/refine/pose_fit.hpp"
#include "host/detect/refine/pose_refine.hpp"
#include "host/detect/verify/lookalike_holes.hpp"
#include "host/detect/verify/verify_candidates.hpp"
#include "host/core/timing.hpp"
#include "host/core/gripper.hpp"
#include "host/core/mesh.hpp"
#include "host/train/ppf_model.hpp"
#include "host/detect/scene/cloud_image.hpp"
#include "host/detect/scene/depth_to_points.hpp"

namespace binpick {

struct BinFit;
class SharedScene;

// Time per stage over the work done (ms), for the summary line and the benchmark.
struct DetectTimes {
  double prepare_ms = 0;  // scene preparation, highest points, crops, subsampling
  double vote_ms = 0;     // features, votes, peaks
  double cluster_ms = 0;  // poses, compatibility, grouping
  double refine_ms = 0;   // refinement and verification
  double pick_ms = 0;     // pick planning (--picks)
  std::size_t hypotheses = 0;
  std::size_t bin_sought = 0, bin_found = 0;  // images a bin was looked for in, and found in
  // Per image with a confident pose (fit >= --confident): ms from the start of its detection to
  // the end of the round that verified it.
  std::vector<double> first_confident_ms;
  StageTimings stages;    // every stage in order, for --verbose
  DetectTimes& operator+=(const DetectTimes& o);
  double total_ms() const { return prepare_ms + vote_ms + cluster_ms + refine_ms + pick_ms; }
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
  std::vector<Detection> detect(DepthView depth, const bp_camera& cam,
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
  // Of the last detect() on a depth image: the bin fitted or given, when one was asked for.
  const std::optional<BinFit>& last_bin() const { return last_bin_; }
  // With picks planned (picks_wanted): the gripper they are planned for.
  const std::optional<Gripper>& gripper() const { return gripper_; }
  // Of the last detect(): when the first confident pose came and why detection stopped, or "".
  const std::string& rounds_report() const { return rounds_report_; }
  static constexpr std::size_t kMinCropPoints = 10;

 private:
  // Reference points, votes, clusters of a subsampled neighbourhood with normals: the best
  // `candidates` clusters, most voted first.
  // ref_ratio: of the coarse ranking (prerank.hpp); 0: --ref-ratio.
  std::vector<PoseCluster> vote_and_cluster(const PointCloud& subsampled, Detection& d,
                                            DetectTimes& t, double ref_ratio = 0);
  // The order the `found` highest points are voted in: with --prerank the first `ranked` by a
  // coarse vote on crop(k) (those with a reason last), the rest by height (prerank.hpp). Adds a
  // stage to t.
  std::vector<std::size_t> vote_order(
      std::size_t found, std::size_t ranked,
      const std::function<const HypothesisCrop&(std::size_t)>& crop, DetectTimes& t);
  // The highest points in the order they are voted in (vote_order), the next to take, and, on
  // a depth image, more(): finds more highest points and appends them (false: there are none),
  // as many more as were flat-skipped (*flat_skipped, counted as they are passed).
  struct VoteQueue {
    std::vector<std::size_t> order;
    std::size_t next = 0;
    std::function<bool()> more;
    std::size_t* flat_skipped = nullptr;
  };
  // What the rounds voted: a detection per highest point voted on and its candidate clusters.
  struct Voted {
    std::vector<Detection> detections;
    std::vector<std::vector<PoseCluster>> candidates;
  };
  // in_rounds' vote(from, to) on a depth image and a cloud alike: takes highest points from the
  // queue until to - from are voted on or skipped (their crop's reason goes to skipped_); one
  // the flat-region test skips does not count, the next stands in. Adds to t.hypotheses; the
  // vote's time is kept out of clock (preparation).
  void vote_from_queue(VoteQueue& queue, std::size_t from, std::size_t to,
                       const std::function<const HypothesisCrop&(std::size_t)>& crop,
                       const std::vector<Hypothesis>& hyps, std::vector<PointCloud>* neighbourhoods,
                       Voted& voted, Stopwatch& clock, DetectTimes& t);
  // Refines and verifies every hypothesis' candidates against a point image on the device
  // (one batch for all), keeps each hypothesis' best and ranks them. With a bin found, a pose
  // that sinks the part into its floor scores 0 (below_floor.hpp). sensor: the points are a
  // sensor's depth image. Not for a cloud seen through a virtual camera (scene_cloud.hpp),
  // whose empty pixels are only gaps between points and whose depths are the nearest point's
  // in a pixel, not the surface along the ray: the look-alike holes (lookalike_holes.hpp), which
  // weigh millimetres of depth at a few hundred points, run only on a sensor's image (on a
  // shaft's cloud they turned a right pose end for end:
  // docs/decisions/2026-11-25-lookalike-holes.md).
  // vote(from, to) votes on the hypotheses [from, to) and keeps them; rank() refines,
  // verifies and ranks all kept so far. The first `hypotheses` of the `found`, then, if no pose
  // scores `confident` or more, the rest as well, all ranked together. With `instances`, all
  // in one round.
  // With --stop-at-confident or --budget-ms, one hypothesis a round instead, in vote order,
  // until a confident pose (with the former) or the budget spent (the latter). started: the
  // image's detection began; t: gets the time to the first confident pose.
  std::vector<Detection> in_rounds(std::size_t found,
                                   const std::function<void(std::size_t, std::size_t)>& vote,
                                   const std::function<std::vector<Detection>()>& rank,
                                   const Stopwatch& started, DetectTimes& t);
  std::vector<Detection> refine_and_rank(std::vector<Detection> detections,
                                         const std::vector<std::vector<PoseCluster>>& candidates,
                                         const ocl::Buffer<float>& points, const bp_camera& cam,
                                         DetectTimes& t, bool sensor, const BinFit* bin = nullptr,
                                         PlaneSearchMemo* searched_before = nullptr,
                                         RefineMemo* refined = nullptr,
                                         const ocl::Buffer<float>* search_points = nullptr);
  // A cloud's points in the region (--roi, --bin; all of them without one), found on the depth
  // image of its virtual camera (detector_cloud.cpp), and the bin when one was sought.
  struct CloudRegion {
    PointCloud kept;
    std::optional<BinFit> bin;
  };
  CloudRegion cloud_region(const CloudImage& image, const PointCloud& cloud, DetectTimes& t);
  // The region options (--roi, --bin and the rules scaled by the part) for an image whose depth
  // noise is `noise` mm.
  RegionSetup region_setup(double noise) const;
  // Keeps what the region found (last_bin_, the report --verbose prints, the counts in t) and
  // warns once when a bin asked for was not found. depth: the image the mask is of.
  void note_region(const SceneRegionMask& masked, const RegionSetup& region, DepthView depth,
                   DetectTimes& t);
  // With a gripper, each detection's pick against the point image (plan_picks.hpp), timed in t.
  // noise: the image's depth noise in mm (it widens the collision tolerance); bin: if found.
  void add_picks(std::vector<Detection>& detections, const ocl::Buffer<float>& points,
                 const bp_camera& cam, const BinFit* bin, double noise, DetectTimes& t);

  ocl::Device& dev_;
  double program_build_s_ = 0;
  std::vector<Detection> skipped_;
  std::string region_report_;
  std::string rounds_report_;
  double image_noise_ = 0;  // mm, the depth image's noise (depth_noise.hpp), for the near gate
  // The "no bin found" warning is printed once per Detector, and only for a bin of a given size:
  // `auto` (the default) is content to find none (DetectTimes counts the images it found one in).
  bool warned_no_bin_ = false;
  const PpfModel& model_;
  DetectParams params_;
  // The bin asked for: --bin, or the one --bin-pose gives (read once, here).
  BinSpec bin_spec_;
  // --picks: the grasps (the model's or --grasps') and the gripper; none without picks.
  std::vector<Grasp> grasps_;
  std::optional<Gripper> gripper_;
  // What identifies it among the fits an image's models share (shared_scene.hpp).
  std::string bin_key() const {
    return params_.bin_pose.empty() ? params_.bin : "pose:" + params_.bin_pose;
  }
  // The bin of the last depth image's region (when one was asked for).
  std::optional<BinFit> last_bin_;
  DeviceModel device_model_;
  DeviceFitModel fit_model_;
  // The fit points followed by the look-alikes' probes and the edge probes (lookalike_holes.hpp);
  // empty without probes.
  DeviceFitModel probe_fit_model_;
  PlaneSearchModel plane_search_model_;  // thin parts with --plane-search only
  ProbeModel probes_;
  VerifyCandidatesOptions verify_options_;  // from params_
  FitGeometry fit_geometry_;
  float outline_ratio_ = 0;  // the verification's outline, 0 for thin parts (outline.hpp)
  double thinnest_extent_ = 0;  // mm, the model's extent along its least-variance axis
  std::optional<FlatRegionSkip> flat_skip_;  // --flat-region (flat_region.hpp)
};

}  // namespace binpick
