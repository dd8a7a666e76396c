// `binpick detect`: finds the part in every scene of a BOP dataset (or in one point cloud) with
// point pair feature voting around the highest points (paper section III-B/C) and writes the
// BOP results CSV, one row per hypothesis, best first.
#include <CLI/CLI.hpp>
#include <chrono>
#include <optional>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "host/formats/bop/results_csv.hpp"
#include "host/app/output_file.hpp"
#include "host/app/verbs/verbs.hpp"
#include "host/core/error.hpp"
#include "host/core/output_lock.hpp"
#include "host/detect/batch/detect_batch.hpp"
#include "host/detect/detector.hpp"
#include "host/detect/batch/picks_csv.hpp"
#include "host/formats/mesh/point_cloud_ply.hpp"
#include "host/core/atomic_file.hpp"
#include "host/core/read_file.hpp"
#include "host/train/ppf_model_file.hpp"
#include "host/app/detect_models.hpp"
#include "host/app/options/detect_options.hpp"
#include "host/app/options/shard_options.hpp"
#include "host/detect/batch/detect_parts.hpp"
#include "host/shards/slurm_run.hpp"
#include "host/train/model_store.hpp"
#include "host/core/timing.hpp"

namespace binpick::cli {
namespace {

namespace fs = std::filesystem;

struct DetectArgs {
  std::vector<std::string> models;  // --model, repeated: .ppfm files or directories of them
  std::vector<int> obj_ids;         // --obj-id, once per --model or not at all
  std::string dataset, cloud, out, scenes, split = "test", sensor, targets, save_bin_pose;
  bool verbose = false;
  DetectCliOptions detection;  // --params and one option per parameter
  ShardCliOptions shards;      // --shard K/N, --slurm
};

// --slurm: the batch's shards as a job array; the parts are done when they carry this run's
// fingerprint, so changed options resubmit every shard.
void detect_on_slurm(const DetectArgs& a, const BatchOptions& opt, const DetectParams& params) {
  const std::vector<int> scenes = batch_scenes(opt);
  const std::string fingerprint = batch_fingerprint(opt, params);
  const fs::path stamp = parts_dir(opt.out) / "fingerprint.json";
  // Until a task has stamped OUT.parts with this run's fingerprint, parts there are another
  // run's; once stamped, it stays this run's.
  auto same_run = std::make_shared<bool>(false);
  const auto done = [=, &opt](int scene) {
    if (!*same_run) *same_run = fs::is_regular_file(stamp) && read_file_bytes(stamp) == fingerprint;
    return *same_run && scene_done(opt.out, scene);
  };
  ShardRecord record = batch_shard_record(opt, scenes);
  record.shards = a.shards.slurm.tasks;
  const ShardedBatch batch{parts_dir(opt.out), record, done, [&] {
    const std::size_t rows = merge_detect_parts(opt.out, scenes);
    return fmt::format("merged {} scenes ({} rows); wrote {}", scenes.size(), rows,
                       opt.out.string());
  }};
  run_on_slurm(batch, a.shards.slurm, task_command(own_command_line()), std::cout);
}

// Detection in one point cloud (--cloud), by every model; written as scene 0, image 0.
void detect_cloud(const DetectArgs& a, const std::vector<ObjectDetector>& detectors) {
  const auto start = std::chrono::steady_clock::now();
  const PointCloud cloud = read_point_cloud_ply(a.cloud);
  const bool several = detectors.size() > 1;
  BatchSummary s;
  s.scenes = s.images = 1;
  std::vector<std::vector<Detection>> found;
  for (const ObjectDetector& d : detectors) {
    try {
      found.push_back(d.detector->detect(cloud, &s.times));
    } catch (const InputError& e) {
      throw InputError(a.cloud + ": " + e.what());
    }
  }
  const double seconds = seconds_since(start);
  std::vector<bop::ResultRow> rows;
  std::string details = details_header(several);
  for (std::size_t m = 0; m < detectors.size(); ++m) {
    const auto image_rows = detection_rows(found[m], 0, 0, detectors[m].obj_id, seconds);
    rows.insert(rows.end(), image_rows.begin(), image_rows.end());
    details += detail_rows(found[m], 0, 0,
                           several ? std::optional<int>(detectors[m].obj_id) : std::nullopt);
  }
  write_file_atomically(details_path(a.out), [&](std::ostream& o) { o << details; });
  if (detectors.front().detector->gripper()) {  // every model plans picks, or none
    std::string picks = kPicksCsvHeader;
    for (std::size_t m = 0; m < detectors.size(); ++m)
      picks += pick_rows(found[m], 0, 0, detectors[m].obj_id,
                         detectors[m].detector->gripper()->describe());
    write_file_atomically(picks_path(a.out), [&](std::ostream& o) { o << picks; });
  }
  bop::write_results_csv(a.out, rows);
  s.rows = rows.size();
  if (a.verbose) {
    for (const StageTime& st : s.times.stages)
      std::cout << fmt::format("  {} {:.1f} ms\n", st.stage, st.ms);
    for (const ObjectDetector& d : detectors)  // what --roi / --bin found on the cloud's image
      if (!d.detector->region_report().empty())
        std::cout << "  " << (several ? fmt::format("obj_id {} ", d.obj_id) : "")
                  << d.detector->region_report() << "\n";
    for (std::size_t m = 0; m < detectors.size(); ++m)
      for (std::size_t r = 0; r < found[m].size(); ++r)
        std::cout << "  " << (several ? fmt::format("obj_id {} ", detectors[m].obj_id) : "")
                  << detection_line(r, found[m][r]) << "\n";
  }
  std::cout << summary_line(s) << "\nwrote " << a.out << "\n";
}

void run_detect(DetectArgs& a) {
  if (a.dataset.empty() == a.cloud.empty())
    throw InputError("give exactly one of --dataset DIR and --cloud FILE.ply");
  const DetectParams params = resolve(a.detection);
  const Shard shard = shard_of(a.shards);
  check_output_file(a.out);
  // A shard shares the output with the other shards; --slurm's follower only waits for its
  // tasks (which lock as shards) and merges after them.
  std::optional<OutputLock> lock;
  if (!a.shards.slurm.enabled) lock.emplace(OutputLock::file(a.out, shard.index, shard.count));
  const std::vector<ModelSource> sources = resolve_model_sources(a.models, a.obj_ids);
  if (!a.cloud.empty()) {
    if (!a.scenes.empty()) throw InputError("--scenes applies to --dataset only");
    if (!a.targets.empty()) throw InputError("--targets applies to --dataset only");
    if (!a.save_bin_pose.empty()) throw InputError("--save-bin-pose applies to --dataset only");
    if (shard.sharded() || a.shards.slurm.enabled)
      throw InputError("--shard and --slurm apply to --dataset only (a --cloud is one scene)");
  }
  std::vector<LoadedModel> models;
  models.reserve(sources.size());  // the detectors keep references to the models
  for (const ModelSource& source : sources) {
    models.push_back(load_model_source(source));
    if (models.back().train_seconds > 0)
      std::cout << fmt::format("trained {} (obj_id {}) in {:.1f} s\n", source.path.string(),
                               source.obj_id, models.back().train_seconds);
  }

  BatchOptions opt;
  opt.dataset = a.dataset;
  opt.split = a.split;
  opt.sensor = a.sensor;
  if (!a.scenes.empty()) opt.scenes = parse_scene_list(a.scenes);
  opt.obj_id = models.front().source.obj_id;
  opt.out = a.out;
  opt.model_checksum = models.front().checksum;
  for (const LoadedModel& m : models) opt.models.push_back({m.checksum, m.source.obj_id});
  opt.verbose = a.verbose;
  opt.shard = shard;
  if (!a.save_bin_pose.empty()) {
    if (shard.sharded() || a.shards.slurm.enabled)
      throw InputError("--save-bin-pose writes the bin of one image: not with --shard or --slurm");
    if (params.bin == "none" || !params.bin_pose.empty())
      throw InputError("--save-bin-pose writes the bin found in an image: it needs --bin auto or "
                       "--bin W,D,H, not --bin none or --bin-pose");
    check_output_file(a.save_bin_pose);
    opt.save_bin_pose = a.save_bin_pose;
  }
  if (!a.targets.empty()) {
    if (params.instances > 0)
      throw InputError("--targets sets each image's instance budget from the file; leave out "
                       "--instances (and \"instances\" in --params)");
    opt.targets = read_detect_targets(a.targets);
  }
  if (a.cloud.empty() && a.shards.slurm.enabled) return detect_on_slurm(a, opt, params);
  std::vector<std::unique_ptr<Detector>> owned;
  std::vector<ObjectDetector> detectors;
  for (const LoadedModel& m : models) {
    owned.push_back(std::make_unique<Detector>(m.model, params));
    detectors.push_back({owned.back().get(), m.source.obj_id});
  }
  if (!a.cloud.empty()) return detect_cloud(a, detectors);
  const BatchSummary s = detect_dataset(detectors, opt, &std::cout);
  std::cout << summary_line(s) << "\n";
  if (s.missing == 0)
    std::cout << "wrote " << a.out << "\n";
  else
    std::cout << fmt::format("shard {} done; {} scenes of other shards still to do: the shard "
                             "that finishes last writes {} (or `binpick merge {}`)\n",
                             shard.name(), s.missing, a.out, a.out);
}

}  // namespace

void add_detect_verb(CLI::App& app) {
  auto a = std::make_shared<DetectArgs>();
  auto* verb = app.add_subcommand(
      "detect",
      "Find the part around the highest points of every scene of a BOP dataset (or of a point "
      "cloud) with point pair feature voting on the OpenCL device; write the BOP results CSV");
  verb->add_option("--model", a->models,
                   "trained model (.ppfm, from `binpick train`); repeat for several objects, or "
                   "give a directory of obj_NNNNNN.ppfm files (or a BOP models/ folder: "
                   "models_info.json and obj_NNNNNN.ply, trained here with train's defaults)")
      ->required();
  verb->add_option("--dataset", a->dataset, "BOP dataset directory (DIR/SPLIT/NNNNNN/depth/...)");
  verb->add_option("--cloud", a->cloud,
                   "instead of --dataset: one scene as a .ply point cloud in the camera frame "
                   "(mm, z along the viewing axis), with or without normals");
  verb->add_option("--out", a->out, "results CSV to write (BOP format)")->required();
  verb->add_option("--split", a->split, "dataset split directory")->capture_default_str();
  verb->add_option("--sensor", a->sensor,
                   "BOP sensor suffix: read scene_camera_NAME.json and depth_NAME/ (BOP's "
                   "industrial datasets)");
  verb->add_option("--scenes", a->scenes, "subset of scene ids, e.g. 0,3,5-9 (default: all)");
  verb->add_option("--obj-id", a->obj_ids,
                   "object id written in the results, once per --model in the same order "
                   "(default: from a BOP name obj_NNNNNN.ppfm, else 1 for a single model)");
  verb->add_option("--targets", a->targets,
                   "BOP target list (e.g. DATASET/test_targets_bop19.json): each model detects "
                   "only in the images listing its obj_id, with their inst_count as its "
                   "--instances budget; images listing none are not read");
  verb->add_flag("--verbose", a->verbose, "print per-stage timings of every image");
  verb->add_option("--save-bin-pose", a->save_bin_pose,
                   "write the bin found in the first image (in scene order) that has one as a "
                   "--bin-pose file: a fixed cell's calibration, e.g. with --scenes 0 and --bin "
                   "W,D,H (docs/formats.md); the run fails if no image has one");
  add_detect_cli_options(verb, a->detection, "detection");
  add_shard_options(verb, a->shards, "scenes");
  verb->callback([a] { run_detect(*a); });
}

}  // namespace binpick::cli
