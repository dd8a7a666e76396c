// Detection over the scenes of a BOP dataset (`binpick detect --dataset`), resumable: each
// scene's rows go to OUT.parts/scene_NNNNNN.csv (and .details.csv) as soon as it is done, next to a fingerprint of
// the run (model file checksum, object id, split and parameters). A rerun with the same
// fingerprint skips the scenes already there; another fingerprint starts over. At the end all
// requested scenes are merged, in scene order, into OUT (atomically). The parts stay, so a
// rerun is only the merge.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "host/formats/bop/results_csv.hpp"
#include "host/detect/batch/detect_targets.hpp"
#include "host/detect/detector.hpp"
#include "host/detect/scene/depth_to_points.hpp"
#include "host/shards/shard.hpp"
#include "host/shards/shard_record.hpp"

namespace binpick {

// One model of a batch: the checksum of its file (the fingerprint) and the obj_id of its rows.
struct BatchModel {
  std::string checksum;
  int obj_id = 1;
};

struct BatchOptions {
  std::filesystem::path dataset;
  std::string split = "test";
  std::string sensor;       // BOP sensor suffix ("": none): scene_camera_SENSOR.json, depth_SENSOR/
  std::vector<int> scenes;  // ascending, unique; empty: every scene of the split
  int obj_id = 1;
  std::filesystem::path out;
  std::string model_checksum;  // part of the fingerprint
  // Several models (detect --model repeated), ascending by obj_id: their checksums and obj_ids
  // make the fingerprint instead of model_checksum and obj_id. Empty or one: the single model's.
  std::vector<BatchModel> models;
  bool verbose = false;        // per-image stage timings to the log
  Shard shard;                 // --shard K/N: only the scenes at positions K-1, K-1+N, ...
  // --targets: each model detects only in the images that list its obj_id, with their
  // inst_count as its instance budget (detect_targets.hpp); images listing none are skipped.
  std::optional<DetectTargets> targets;
  // Non-empty: the bin of the first image (in scene order) whose detection found one is written
  // there as a --bin-pose file (bin_pose_file.hpp); InputError at the end if none had one.
  std::filesystem::path save_bin_pose;
};

struct BatchSummary {
  std::size_t scenes = 0, skipped = 0, images = 0, rows = 0;
  std::size_t untargeted = 0;  // images not read: --targets lists none of the models there
  std::size_t missing = 0;  // scenes of the batch not done yet (other shards'): OUT not merged
  DetectTimes times;  // of the scenes run now (not the skipped ones)
  double program_build_s = 0;  // the detector's OpenCL program builds, outside every image's time
  bool bin_pose_saved = false;  // BatchOptions::save_bin_pose written
};

// The scene ids of DATASET/SPLIT (directories named by a number), ascending. InputError if the
// split directory does not exist or holds no scene.
std::vector<int> list_scenes(const std::filesystem::path& dataset, const std::string& split);

// Parses "0,3,5-9" into ids. InputError for anything else.
std::vector<int> parse_scene_list(const std::string& text);

// The camera of one image: K and depth_scale from scene_camera.json, size from the image.
bp_camera image_camera(const Eigen::Matrix3d& K, double depth_scale, std::uint32_t width,
                       std::uint32_t height);

// A detector and the obj_id its rows are written with (detect_dataset with several models).
struct ObjectDetector {
  Detector* detector = nullptr;
  int obj_id = 1;
};

// The rows of one image (best first), with `time` its seconds.
std::vector<bop::ResultRow> detection_rows(const std::vector<Detection>& detections, int scene_id,
                                           int im_id, int obj_id, double seconds);

// Beside the results OUT (BOP's CSV, whose score column is the verified score), OUT with the
// extension .details.csv: per detection its rank, hypothesis, candidate cluster, score, votes,
// visible and agreeing model points, one column per factor of the score (score.hpp, in their
// order: their product is the score; rival_cap is empty where no rival capped it), and the
// reason of a 0 score or a refinement cut short.
std::filesystem::path details_path(const std::filesystem::path& out);
// The header line; with several models an obj_id column follows im_id (rank is then per obj_id).
std::string details_header(bool with_obj_id);
// obj_id: the column's value with several models; none with one (the column left out).
std::string detail_rows(const std::vector<Detection>& detections, int scene_id, int im_id,
                        std::optional<int> obj_id = std::nullopt);
// The hypotheses skipped before voting (Detector::skipped), after an image's detections: rank
// empty (they are not results), score and counts 0, the reason why.
std::string skipped_rows(const std::vector<Detection>& skipped, int scene_id, int im_id,
                         std::optional<int> obj_id = std::nullopt);

// One detection for --verbose: rank, hypothesis, score and its counts, votes, and the reason of
// a 0 score or a refinement cut short.
std::string detection_line(std::size_t rank, const Detection& d);

// The batch's scenes: opt.scenes, or every scene of the split; InputError for a scene of
// opt.shard's that is not in the dataset.
std::vector<int> batch_scenes(const BatchOptions& opt);

// What the parts of a batch are made with (model checksum, object id, split, sensor, dataset,
// parameters): parts with another fingerprint are not reused.
std::string batch_fingerprint(const BatchOptions& opt, const DetectParams& params);

// The batch as a sharded one (detect_parts.hpp's shards.json).
ShardRecord batch_shard_record(const BatchOptions& opt, const std::vector<int>& scenes);

// Runs the batch (with opt.shard: its share) and, once every scene of the batch is done,
// merges the parts into OUT; progress on stderr, the log (verbose lines) to `log` if given.
BatchSummary detect_dataset(Detector& detector, const BatchOptions& opt, std::ostream* log);
// The same with several models (ascending by obj_id, of equal parameters): each image's depth is
// read and prepared once, its bin fitted once (shared_scene.hpp), and every model detects in it; its rows are those of each model in turn (BOP's
// order: obj_id, then score), each model's --instances budget its own; the image's time is that
// of all of them.
BatchSummary detect_dataset(const std::vector<ObjectDetector>& detectors, const BatchOptions& opt,
                            std::ostream* log);

// "N scenes (K skipped), H hypotheses; ms per hypothesis: preparation P, voting V,
// clustering C, refinement F, total T", then the program builds' seconds if the detector paid any.
std::string summary_line(const BatchSummary& s);

}  // namespace binpick
