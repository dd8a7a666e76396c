#include "host/detect/batch/detect_batch.hpp"

#include "host/core/csv_quote.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <ostream>

#include <fmt/format.h>

#include "host/formats/bop/bop_files.hpp"
#include "host/formats/bop/scene_files.hpp"
#include "host/formats/bop/png_image.hpp"
#include "host/core/error.hpp"
#include "host/core/progress.hpp"
#include "host/core/quantile.hpp"
#include "host/detect/params/bin_pose_file.hpp"
#include "host/detect/params/params_file.hpp"
#include "host/detect/batch/detect_parts.hpp"
#include "host/detect/shared_scene.hpp"
#include "host/detect/batch/picks_csv.hpp"
#include "host/shards/shard_record.hpp"
#include "host/core/atomic_file.hpp"
#include "host/core/read_file.hpp"
#include "host/train/model_store.hpp"
#include "host/core/timing.hpp"

namespace binpick {
namespace fs = std::filesystem;
namespace {

bool parse_int(std::string_view s, int& value) {
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  return !s.empty() && ec == std::errc() && end == s.data() + s.size() && value >= 0;
}

}  // namespace

std::vector<int> list_scenes(const fs::path& dataset, const std::string& split) {
  const fs::path dir = dataset / split;
  if (!fs::is_directory(dir))
    throw InputError("dataset " + dataset.string() + " has no split directory '" + split + "'");
  std::vector<int> ids;
  for (const auto& entry : fs::directory_iterator(dir)) {
    int id = 0;
    if (entry.is_directory() && parse_int(entry.path().filename().string(), id)) ids.push_back(id);
  }
  std::sort(ids.begin(), ids.end());
  if (ids.empty()) throw InputError(dir.string() + " holds no scene directory");
  return ids;
}

std::vector<int> parse_scene_list(const std::string& text) {
  std::vector<int> ids;
  std::string_view rest = text;
  while (!rest.empty()) {
    const std::size_t comma = rest.find(',');
    const std::string_view item = rest.substr(0, comma);
    rest = comma == rest.npos ? std::string_view() : rest.substr(comma + 1);
    const std::size_t dash = item.find('-');
    int lo = 0, hi = 0;
    const bool ok = dash == item.npos
                        ? parse_int(item, lo) && (hi = lo, true)
                        : parse_int(item.substr(0, dash), lo) && parse_int(item.substr(dash + 1), hi);
    if (!ok || hi < lo || hi - lo > 1000000)
      throw InputError("--scenes '" + text + "': expected ids and ranges like 0,3,5-9");
    for (int id = lo; id <= hi; ++id) ids.push_back(id);
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  if (ids.empty()) throw InputError("--scenes is empty");
  return ids;
}

bp_camera image_camera(const Eigen::Matrix3d& K, double depth_scale, std::uint32_t width,
                       std::uint32_t height) {
  return {float(K(0, 0)), float(K(1, 1)), float(K(0, 2)), float(K(1, 2)), float(depth_scale),
          width, height, 0};
}

std::vector<bop::ResultRow> detection_rows(const std::vector<Detection>& detections, int scene_id,
                                           int im_id, int obj_id, double seconds) {
  std::vector<bop::ResultRow> rows;
  for (const Detection& d : detections)
    rows.push_back({scene_id, im_id, obj_id, d.score(), d.R, d.t, seconds});
  return rows;
}

fs::path details_path(const fs::path& out) {
  fs::path p = out;
  return p.replace_extension(".details.csv");
}

namespace {

// "OBJ_ID," with several models, "" with one.
std::string obj_id_column(std::optional<int> obj_id) {
  return obj_id ? fmt::format("{},", *obj_id) : std::string();
}

}  // namespace

std::string details_header(bool with_obj_id) {
  std::string header = with_obj_id ? "scene_id,im_id,obj_id,rank" : "scene_id,im_id,rank";
  header += ",hypothesis,candidate,score,votes,visible,inliers";
  for (const ScoreFactorInfo& f : score_factors()) header += std::string(",") + f.name;
  return header + ",reason\n";
}

std::string detail_rows(const std::vector<Detection>& detections, int scene_id, int im_id,
                        std::optional<int> obj_id) {
  std::string text;
  for (std::size_t r = 0; r < detections.size(); ++r) {
    const Detection& d = detections[r];
    text += fmt::format("{},{},{}{},{},{},{:.6f},{},{},{}{},{}\n", scene_id, im_id,
                        obj_id_column(obj_id), r, d.index, d.candidate, d.score(), d.votes,
                        d.evidence.visible, d.evidence.inliers, factor_columns(d.breakdown),
                        d.reason.empty() ? "" : csv_quoted(d.reason));
  }
  return text;
}

std::string skipped_rows(const std::vector<Detection>& skipped, int scene_id, int im_id,
                         std::optional<int> obj_id) {
  const std::string no_factors(kScoreFactorCount, ',');
  std::string text;
  for (const Detection& d : skipped)
    text += fmt::format("{},{},{},{},0,0.000000,0,0,0{},{}\n", scene_id, im_id,
                        obj_id_column(obj_id), d.index, no_factors, csv_quoted(d.reason));
  return text;
}

std::string detection_line(std::size_t rank, const Detection& d) {
  const PoseEvidence& e = d.evidence;
  std::string line = fmt::format(
      "#{} hypothesis {} candidate {}: score {:.3f} = {} ({} of {} visible model points agree), "
      "{} votes",
      rank, d.index, d.candidate, d.score(), describe_factors(d.breakdown), e.inliers, e.visible,
      d.votes);
  if (e.outline_continue + e.outline_step > 0)
    line += fmt::format("; outline steps down at {} of {} cells", e.outline_step,
                        e.outline_continue + e.outline_step);
  if (e.patches_tested > 0)
    line += fmt::format("; {} of {} patches biased", e.patches_biased, e.patches_tested);
  if (e.ray_tested)
    line += fmt::format("; {:.2f} mm spread along the rays beyond the noise", e.ray_excess);
  if (e.lookalike_tested)
    line += fmt::format("; {:.2f} mm seen through where a look-alike has a hole",
                        e.lookalike_excess);
  if (e.edge_tested) line += fmt::format("; edges step down by {:.2f} mm", e.edge_step);
  if (e.area_tested) line += fmt::format("; shows {:.2f} of its mean area", e.area_share);
  if (std::isfinite(d.breakdown[kRivalCap]))
    line += fmt::format("; out-fitted by a rival pose on {} shared points ({:.2f} against {:.2f} mm^2)",
                        e.rival_shared, e.own_ms, e.rival_ms);
  if (e.lookalike_score > 0)
    line += fmt::format("; a look-alike scores {:.3f}", e.lookalike_score);
  if (e.see_through > 0) line += fmt::format("; {} seen through", e.see_through);
  if (!d.reason.empty()) line += "; " + d.reason;
  return line;
}

std::vector<int> batch_scenes(const BatchOptions& opt) {
  bop::check_sensor_name(opt.sensor);
  if (opt.scenes.empty()) return list_scenes(opt.dataset, opt.split);
  // Only this shard's scenes must be there: other shards (of `run`) may still be making theirs.
  std::vector<int> available;
  for (std::size_t p = 0; p < opt.scenes.size(); ++p) {
    if (!opt.shard.owns(p)) continue;
    if (available.empty()) available = list_scenes(opt.dataset, opt.split);
    if (!std::binary_search(available.begin(), available.end(), opt.scenes[p]))
      throw InputError(fmt::format("scene {} is not in {}", opt.scenes[p],
                                   (opt.dataset / opt.split).string()));
  }
  return opt.scenes;
}

std::string batch_fingerprint(const BatchOptions& opt, const DetectParams& params) {
  std::string models = fmt::format("\"model\": \"{}\", \"obj_id\": {}", opt.model_checksum,
                                   opt.obj_id);
  if (opt.models.size() > 1) {
    models = "\"models\": [";
    for (std::size_t i = 0; i < opt.models.size(); ++i)
      models += fmt::format("{}{{\"model\": \"{}\", \"obj_id\": {}}}", i ? ", " : "",
                            opt.models[i].checksum, opt.models[i].obj_id);
    models += "]";
  }
  // Without --targets the fingerprint is what it was before the option existed (parts resume).
  const std::string targets =
      opt.targets ? fmt::format(", \"targets\": \"{}\"", opt.targets->checksum) : "";
  // The files the parameters name, by their bytes: an edited bin pose or bin mesh is another run
  // (absent when none is named, so that other runs' parts resume).
  std::string files;
  const auto add = [&](const char* key, const std::string& path) {
    files += fmt::format("{}\"{}\": \"{}\"", files.empty() ? "" : ", ", key,
                         checksum_hex(read_file_bytes(path)));
  };
  if (!params.bin_pose.empty()) add("bin-pose", params.bin_pose);
  if (!params.grasps.empty()) add("grasps", params.grasps);
  if (params.gripper.ends_with(".json")) add("gripper", params.gripper);
  if (params.bin.rfind("mesh:", 0) == 0) add("bin-mesh", params.bin.substr(5));
  if (!files.empty()) files = ", \"files\": {" + files + "}";
  return fmt::format(
      "{{{}, \"split\": \"{}\", \"sensor\": \"{}\", \"dataset\": \"{}\", \"params\": {}{}{}}}\n",
      models, opt.split, opt.sensor, fs::absolute(opt.dataset).string(), params_json(params),
      targets, files);
}

ShardRecord batch_shard_record(const BatchOptions& opt, const std::vector<int>& scenes) {
  return {"detect", fs::absolute(opt.out), scenes, opt.shard.count};
}

namespace {

// One image of the batch: every model detects in it, in turn; their rows (each model's best
// first) and details are appended, all with the image's time.
// `several`: the batch has several models (the details' obj_id column), even when --targets
// leaves one of them for this image.
void detect_image(const std::vector<ObjectDetector>& detectors, bool several,
                  DepthView depth, const bp_camera& cam, const fs::path& depth_path,
                  int scene, int im_id, std::chrono::steady_clock::time_point start,
                  std::vector<bop::ResultRow>& rows, std::string& details, std::string& picks,
                  BatchSummary& summary, std::ostream* log) {
  std::vector<std::vector<Detection>> found(detectors.size());
  SharedScene shared;  // the image prepared and its bin fitted once, for every model
  for (std::size_t m = 0; m < detectors.size(); ++m) {
    Detector& detector = *detectors[m].detector;
    const int obj_id = detectors[m].obj_id;
    DetectTimes times;
    try {
      found[m] = detector.detect(depth, cam, &times, nullptr, several ? &shared : nullptr);
    } catch (const InputError& e) {
      throw InputError(depth_path.string() + ": " + e.what());
    }
    const std::optional<int> column = several ? std::optional<int>(obj_id) : std::nullopt;
    details += detail_rows(found[m], scene, im_id, column);
    details += skipped_rows(detector.skipped(), scene, im_id, column);
    if (detector.gripper())
      picks += pick_rows(found[m], scene, im_id, obj_id, detector.gripper()->describe());
    if (log) {
      std::string line = fmt::format("scene {} image {}{}: {} hypotheses;", scene, im_id,
                                     several ? fmt::format(" obj_id {}", obj_id) : "",
                                     times.hypotheses);
      for (const StageTime& st : times.stages) line += fmt::format(" {} {:.1f}", st.stage, st.ms);
      *log << line << " ms\n";
      if (!detector.region_report().empty()) *log << "  " << detector.region_report() << "\n";
      if (!detector.rounds_report().empty()) *log << "  " << detector.rounds_report() << "\n";
      for (std::size_t r = 0; r < found[m].size(); ++r)
        *log << "  " << detection_line(r, found[m][r]) << "\n";
      for (const Detection& d : detector.skipped())
        *log << "  hypothesis " << d.index << ": " << d.reason << "\n";
    }
    // The bin is sought once per image (the models share its fit), not once per model.
    if (m > 0) times.bin_sought = times.bin_found = 0;
    summary.times += times;
  }
  // The time of the whole image, every model's detection in it (BOP: one value per image).
  const double seconds = seconds_since(start);
  for (std::size_t m = 0; m < detectors.size(); ++m) {
    const auto image_rows = detection_rows(found[m], scene, im_id, detectors[m].obj_id, seconds);
    rows.insert(rows.end(), image_rows.begin(), image_rows.end());
  }
}

// The models that detect in an image: all of them, or with --targets those whose obj_id the
// image lists, each with its inst_count as budget (the details' obj_id column and the order
// of the rows stay those of the whole batch's models).
std::vector<ObjectDetector> image_detectors(const std::vector<ObjectDetector>& detectors,
                                            const BatchOptions& opt, int scene, int im_id) {
  if (!opt.targets) return detectors;
  std::vector<ObjectDetector> targeted;
  for (const ObjectDetector& d : detectors) {
    const std::uint32_t budget = opt.targets->count(scene, im_id, d.obj_id);
    if (budget == 0) continue;
    d.detector->set_instances(budget);
    targeted.push_back(d);
  }
  return targeted;
}

// --save-bin-pose: the bin the image's first model found or was given, written; false if none.
bool save_bin_pose(const std::vector<ObjectDetector>& detectors, const fs::path& path, int scene,
                   int im_id, std::ostream* log) {
  const std::optional<BinFit>& bin = detectors.front().detector->last_bin();
  if (!bin || !bin->found) return false;
  write_bin_pose(path, bin->axes, bin->origin, bin->interior);
  if (log) *log << fmt::format("wrote the bin of scene {} image {} to {}\n", scene, im_id, path.string());
  return true;
}

}  // namespace

BatchSummary detect_dataset(Detector& detector, const BatchOptions& opt, std::ostream* log) {
  return detect_dataset({{&detector, opt.obj_id}}, opt, log);
}

BatchSummary detect_dataset(const std::vector<ObjectDetector>& detectors, const BatchOptions& opt,
                            std::ostream* log) {
  if (detectors.empty()) throw std::logic_error("detect_dataset without a detector");
  const std::vector<int> scenes = batch_scenes(opt);
  prepare_parts(opt.out, batch_fingerprint(opt, detectors.front().detector->params()));
  write_details_header(opt.out, details_header(detectors.size() > 1));
  const bool picks_on = picks_wanted(detectors.front().detector->params());
  write_picks_marker(opt.out, picks_on);
  // Shards of one batch share OUT.parts; the record tells the merge which scenes make it whole.
  const ShardRecord record = batch_shard_record(opt, scenes);
  const auto done = [&](int scene) { return scene_done(opt.out, scene); };
  if (opt.shard.sharded()) claim_shard_record(shard_record_file(opt.out), record, done);

  BatchSummary summary;
  for (const ObjectDetector& d : detectors) summary.program_build_s += d.detector->program_build_seconds();
  std::size_t own = 0;
  for (std::size_t s = 0; s < scenes.size(); ++s) own += opt.shard.owns(s);
  Progress progress(opt.shard.sharded() ? "detect shard " + opt.shard.name() : "detect", own);
  std::size_t step = 0;
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    if (!opt.shard.owns(s)) continue;
    const int scene = scenes[s];
    ++summary.scenes;
    ++step;
    if (done(scene)) {
      ++summary.skipped;
      progress.update(step, fmt::format("scene {} done before", scene));
      continue;
    }
    const fs::path dir = opt.dataset / opt.split / fmt::format("{:06d}", scene);
    const bop::SceneFiles files{dir, opt.sensor};
    const bop::SceneCameras cameras = bop::read_scene_cameras(files.scene_camera());
    std::vector<bop::ResultRow> rows;
    std::string details, picks;
    for (const auto& [im_id, cam] : cameras) {
      const auto start = std::chrono::steady_clock::now();
      const std::vector<ObjectDetector> targeted = image_detectors(detectors, opt, scene, im_id);
      if (targeted.empty()) {
        ++summary.untargeted;
        continue;
      }
      const fs::path depth_path = files.depth(im_id);
      const GrayImage<std::uint16_t> png = read_png16(depth_path);
      const DepthView depth{png.width, png.height, png.pixels};
      detect_image(targeted, detectors.size() > 1, depth, image_camera(cam.K, cam.depth_scale, png.width, png.height),
                   depth_path, scene, im_id, start, rows, details, picks, summary,
                   opt.verbose ? log : nullptr);
      ++summary.images;
      if (!opt.save_bin_pose.empty() && !summary.bin_pose_saved)
        summary.bin_pose_saved = save_bin_pose(targeted, opt.save_bin_pose, scene, im_id, log);
    }
    // The results part last: its presence marks the scene done.
    write_file_atomically(details_part_file(opt.out, scene), [&](std::ostream& o) { o << details; });
    if (picks_on)
      write_file_atomically(picks_part_file(opt.out, scene), [&](std::ostream& o) { o << picks; });
    bop::write_results_csv(part_file(opt.out, scene), rows);
    progress.update(step, fmt::format("scene {}", scene));
  }

  if (!opt.save_bin_pose.empty() && !summary.bin_pose_saved)
    throw InputError(fmt::format("--save-bin-pose: no bin was found in the {} images detected "
                                 "({} of them done before and not detected again); nothing "
                                 "written to {}",
                                 summary.images, summary.skipped, opt.save_bin_pose.string()));
  // The shard that finds every scene done merges (two finishing at once write the same bytes).
  summary.missing = missing_work(record, done).items.size();
  if (summary.missing == 0) summary.rows = merge_detect_parts(opt.out, scenes);
  progress.finish(summary_line(summary));
  return summary;
}

std::string summary_line(const BatchSummary& s) {
  const DetectTimes& t = s.times;
  const double h = double(std::max<std::size_t>(t.hypotheses, 1));
  const std::string builds =
      s.program_build_s > 0 ? fmt::format("; OpenCL programs built once in {:.2f} s (not counted above)",
                                          s.program_build_s)
                            : "";
  const std::string untargeted =
      s.untargeted > 0 ? fmt::format(" ({} without a target not read)", s.untargeted) : "";
  const std::string bins =
      t.bin_sought > 0 ? fmt::format("; a bin found in {} of {} images", t.bin_found, t.bin_sought)
                       : "";
  std::string confident;
  if (!t.first_confident_ms.empty())
    confident = fmt::format("; a confident pose in {} images, the first after {:.0f} ms (median)",
                            t.first_confident_ms.size(), quantile(t.first_confident_ms, 0.5));
  const std::string picks = t.pick_ms > 0 ? fmt::format(", picks {:.1f}", t.pick_ms / h) : "";
  return fmt::format(
      "{} scenes ({} done before), {} images{}, {} hypotheses, {} rows; ms per hypothesis: "
      "preparation {:.1f}, voting {:.1f}, clustering {:.1f}, refinement {:.1f}{}, total {:.1f}{}{}{}",
      s.scenes, s.skipped, s.images, untargeted, t.hypotheses, s.rows, t.prepare_ms / h, t.vote_ms / h,
      t.cluster_ms / h, t.refine_ms / h, picks, t.total_ms() / h, bins, confident, builds);
}

}  // namespace binpick
