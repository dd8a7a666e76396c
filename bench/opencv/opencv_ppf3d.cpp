// opencv_ppf3d: OpenCV's cv::ppf_match_3d::PPF3DDetector (opencv_contrib's surface_matching,
// Debian 12: OpenCV 4.6) on the crops `binpick bench` writes, so both detectors are timed on the
// same neighbourhoods with the same parameters. Only this executable links OpenCV;
// binpick itself never does. `binpick bench` runs it as a subprocess and reads its JSON.
//
//   opencv_ppf3d --model MODEL.ply --crops DIR --out RESULT.json [options, see --help]
//
// What OpenCV 4.6 does with each parameter (opencv_contrib modules/surface_matching/src/
// ppf_match_3d.cpp and ppf_helpers.cpp), and how binpick's parameters are converted:
//
// - PPF3DDetector(relativeSamplingStep, relativeDistanceStep, numAngles). trainModel computes the
//   model's axis-aligned bounding box and samples the model with
//   samplePCByQuantization(model, bbox, relativeSamplingStep): a grid of
//   N = (int)(1.0 / (float)step) cells along EACH axis, so a cell is (extent of that axis) / N,
//   not a cube; the points of a cell are averaged. The feature distance step is
//   bbox diagonal * relativeSamplingStep: relativeDistanceStep is stored and never used. The
//   angle step is 2 pi / numAngles; alpha gets numAngles bins over [-2 pi, 2 pi] (bins twice as
//   wide, no wrap-around). We pass --sampling, --distance-step and --angles unchanged and report
//   what OpenCV really uses ("opencv_*" fields). Note (int)(1.0 / 0.05f) = 19, not 20.
//
// - match(scene, results, relativeSceneSampleStep, relativeSceneDistance):
//   * relativeSceneSampleStep becomes a stride: OpenCV takes k = (int)(1.0 / step) and uses every
//     k-th sampled scene point as a reference point (loop i += k). For a share of --ref-ratio we
//     pass step = 1 / k with k = round(1 / ref_ratio) (0.2 -> every 5th, 0.02 -> every 50th); the
//     share actually used, 1 / k, is reported as params.effective_ref_ratio. Beware: OpenCV then
//     clusters only the first floor(n / k) of its ceil(n / k) poses (sorted by votes), so a crop
//     with fewer than k sampled points yields no pose at all.
//   * relativeSceneDistance is relative to the SCENE's own bounding box, per axis, exactly as for
//     the model: samplePCByQuantization(scene, scene bbox, relativeSceneDistance), cell =
//     (extent of that axis) / N with N = (int)(1.0 / (float)relativeSceneDistance). It is not
//     relative to the model diameter (the diameter-based line is commented out in match). A crop
//     is already voxel-subsampled by binpick at V mm, so we want OpenCV to keep (nearly) all its
//     points: per crop, N = ceil(largest bbox extent / V), so the largest axis gets cells of at
//     most V mm and the others finer ones (OpenCV cannot make cubic cells), and we pass
//     relativeSceneDistance = 1 / (N + 0.5) so that the float round trip gives exactly N (1/N
//     itself can give N - 1). N is capped at kMaxGridCells: OpenCV allocates (N+1)^3 cells.
//     Each crop's relativeSceneDistance, N and resulting cell sizes are in its JSON entry.
//
// - setSearchParams(positionThreshold, rotationThreshold, useWeightedClustering):
//   * positionThreshold is absolute, in the input's unit (mm here): matchPose compares it with
//     |t_a - t_b|, the distance between the two poses' translations (model -> scene). Its default
//     (-1) is relativeSamplingStep itself, i.e. 0.05 mm: why it must be set. We pass P mm.
//   * rotationThreshold is in radians, compared with |angle_a - angle_b| where angle =
//     acos((trace R - 1) / 2) is each pose's own rotation angle: the difference of two rotation
//     MAGNITUDES, not the angle of R_a^T R_b, so two poses rotated by the same amount about
//     different axes still cluster together. Its default (-1) is (360 / angle_step) / 180 * pi
//     with angle_step already in radians = 30 rad for 30 angles, which exceeds pi and so never
//     bites. We pass --rotation-threshold-deg * pi / 180; it then bites, but only on magnitudes.
//   * Clustering is greedy against each cluster's first (most voted) pose; a cluster's pose is
//     the plain average of its members' quaternions (no sign alignment, not renormalised) and
//     translations; its votes are the sum of its members' peak votes (one peak per reference
//     point). OpenCV builds R from the averaged quaternion q by a formula quadratic in q, so its
//     R is |q|^2 times a rotation: we divide that scale out (it is reported as "quat_norm2").
//
// - Training cost: OpenCV's hash table (t_hash_int.cpp, hashtableInsertHashed) walks a bucket's
//   whole chain before each insert while the keys are equal, and overwrites the first node's data
//   when they differ: quadratic in the pairs sharing a key, and colliding keys lose entries. A
//   model of ~1000 sampled points (a box, whose three normal directions share few keys, or an
//   ellipsoid at --sampling 0.05) takes tens of seconds to minutes to train.
//
// - Debian's build has no OpenMP (no libgomp), so match runs on one thread. --isolate (default
//   on) runs each crop's matches in a forked child process, so that a crash inside OpenCV (its
//   cell and alpha indices are unchecked) loses that crop, reported as an error, not the run.
//   (Checked on Debian's 4.6.0: match frees its per-reference-point accumulator, no leak.)
//
// Timing: std::chrono::steady_clock around trainModel and match only (not file reading or
// conversion); medians over --repeats.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <unordered_set>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/version.hpp>
#include <opencv2/surface_matching.hpp>

#include "host/core/error.hpp"
#include "host/core/atomic_file.hpp"
#include "host/formats/mesh/point_cloud_ply.hpp"

namespace fs = std::filesystem;
using binpick::InputError;
using nlohmann::json;

namespace {

constexpr int kMaxGridCells = 256;  // per axis; OpenCV allocates (N+1)^3 std::vector<int>
constexpr std::size_t kMaxModelPoints = 8000;  // OpenCV stores n^2 pairs (n^2 * 32 bytes)

struct Options {
  fs::path model, crops, out;
  double sampling = 0.05;
  double distance_step = 0.05;
  int angles = 30;
  double ref_ratio = 0.2;
  double scene_voxel_mm = -1;          // default: sampling * model bbox diagonal
  double position_threshold_mm = -1;   // default: 0.144 * model bbox diagonal (the paper's)
  double rotation_threshold_deg = 20;
  int repeats = 1;
  int top = 5;
  bool isolate = true;
};

// An Nx6 CV_32F matrix (x y z nx ny nz), OpenCV's point cloud layout. Normals are renormalised;
// a missing, zero or non-finite normal is bad input.
cv::Mat to_mat(const binpick::PointCloud& cloud, const fs::path& path) {
  if (cloud.normals.size() != cloud.points.size())
    throw InputError(path.string() + ": needs nx ny nz for every vertex (OpenCV's PPF uses normals)");
  cv::Mat m(static_cast<int>(cloud.points.size()), 6, CV_32F);
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    const auto& p = cloud.points[i];
    const auto& n = cloud.normals[i];
    const float len = n.norm();
    if (!n.allFinite() || !(len > 1e-6f))
      throw InputError(path.string() + ": vertex " + std::to_string(i) +
                       " has a zero or non-finite normal");
    float* row = m.ptr<float>(static_cast<int>(i));
    for (int k = 0; k < 3; ++k) {
      row[k] = p[k];
      row[3 + k] = n[k] / len;
    }
  }
  return m;
}

struct Bbox {
  float lo[3], hi[3];
  float extent(int k) const { return hi[k] - lo[k]; }
  float largest() const { return std::max({extent(0), extent(1), extent(2)}); }
  double diagonal() const {
    return std::sqrt(double(extent(0)) * extent(0) + double(extent(1)) * extent(1) +
                     double(extent(2)) * extent(2));
  }
};

// As ppf_helpers.cpp computeBboxStd (float min/max). Requires rows > 0.
Bbox bbox_of(const cv::Mat& m) {
  Bbox b{};
  for (int k = 0; k < 3; ++k) b.lo[k] = b.hi[k] = m.ptr<float>(0)[k];
  for (int i = 0; i < m.rows; ++i) {
    const float* r = m.ptr<float>(i);
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = std::min(b.lo[k], r[k]);
      b.hi[k] = std::max(b.hi[k], r[k]);
    }
  }
  return b;
}

// N = (int)(1.0 / sampleStep) as samplePCByQuantization computes it from the float it receives.
int opencv_grid_cells(double relative_step) {
  const float step = static_cast<float>(relative_step);
  return static_cast<int>(1.0 / step);
}

// How many points samplePCByQuantization keeps: its occupied cells, with its own arithmetic
// (including its aliasing of the far faces, where a coordinate maps to cell N). For reporting.
std::size_t opencv_sampled_count(const cv::Mat& m, const Bbox& b, int n) {
  std::unordered_set<long long> cells;
  const float xr = b.extent(0), yr = b.extent(1), zr = b.extent(2);
  for (int i = 0; i < m.rows; ++i) {
    const float* p = m.ptr<float>(i);
    const int x = static_cast<int>(static_cast<float>(n) * (p[0] - b.lo[0]) / xr);
    const int y = static_cast<int>(static_cast<float>(n) * (p[1] - b.lo[1]) / yr);
    const int z = static_cast<int>(static_cast<float>(n) * (p[2] - b.lo[2]) / zr);
    cells.insert(static_cast<long long>(x) * n * n + static_cast<long long>(y) * n + z);
  }
  return cells.size();
}

// relativeSceneDistance for a crop: N = ceil(largest extent / V) cells on every axis (capped),
// passed as 1 / (N + 0.5) so that OpenCV's (int)(1.0 / float) gives N.
struct SceneGrid {
  int cells;
  double relative_distance;
};
SceneGrid scene_grid(const Bbox& b, double voxel_mm) {
  const double wanted = std::ceil(static_cast<double>(b.largest()) / voxel_mm - 1e-9);
  const int n = static_cast<int>(std::clamp(wanted, 1.0, static_cast<double>(kMaxGridCells)));
  const double rel = 1.0 / (n + 0.5);
  if (opencv_grid_cells(rel) != n) throw std::logic_error("scene grid round trip");
  return {n, rel};
}

// k with (int)(1.0 / (1.0 / k)) == k, as match computes scene_sample_step.
int reference_step(double ref_ratio) {
  return std::max(1, static_cast<int>(std::lround(1.0 / ref_ratio)));
}
double relative_scene_sample_step(int k) {
  double step = 1.0 / k;
  while (static_cast<int>(1.0 / step) < k) step = std::nextafter(step, 0.0);
  return step;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Exposes what trainModel computed (protected members).
class Detector : public cv::ppf_match_3d::PPF3DDetector {
 public:
  using PPF3DDetector::PPF3DDetector;
  int model_points() const { return num_ref_points; }
  double distance_step_used() const { return distance_step; }
  double angle_step_used() const { return angle_step; }
};

// One pose as JSON: R row-major (model -> camera), t in mm, votes.
json pose_json(const cv::ppf_match_3d::Pose3DPtr& p) {
  const double q2 = p->q[0] * p->q[0] + p->q[1] * p->q[1] + p->q[2] * p->q[2] + p->q[3] * p->q[3];
  const double scale = q2 > 1e-12 ? q2 : 1.0;
  json R = json::array(), t = json::array();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R.push_back(p->pose(r, c) / scale);
    t.push_back(p->pose(r, 3));
  }
  return {{"R", R}, {"t", t}, {"votes", p->numVotes}, {"quat_norm2", q2}};
}

struct MatchOutcome {
  std::vector<double> ms;
  json poses = json::array();
  std::string error;
};

MatchOutcome match_in_process(Detector& det, const cv::Mat& scene, double sample_step,
                              double scene_distance, const Options& o) {
  MatchOutcome out;
  std::vector<cv::ppf_match_3d::Pose3DPtr> results;
  try {
    for (int r = 0; r < o.repeats; ++r) {
      results.clear();
      const auto t0 = std::chrono::steady_clock::now();
      det.match(scene, results, sample_step, scene_distance);
      out.ms.push_back(ms_since(t0));
    }
  } catch (const cv::Exception& e) {
    out.error = std::string("OpenCV: ") + e.what();
    return out;
  }
  for (std::size_t i = 0; i < results.size() && i < static_cast<std::size_t>(o.top); ++i)
    out.poses.push_back(pose_json(results[i]));
  return out;
}

// The same in a forked child (see the header: a crash in OpenCV stays contained).
// The child sends back {"ms": [...], "poses": [...], "error": "..."} through a pipe.
MatchOutcome match_isolated(Detector& det, const cv::Mat& scene, double sample_step,
                            double scene_distance, const Options& o) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("pipe failed");
  std::cout.flush();
  std::cerr.flush();
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    throw std::runtime_error("fork failed");
  }
  if (pid == 0) {
    close(fds[0]);
    MatchOutcome m = match_in_process(det, scene, sample_step, scene_distance, o);
    const std::string text = json{{"ms", m.ms}, {"poses", m.poses}, {"error", m.error}}.dump();
    std::size_t done = 0;
    while (done < text.size()) {
      const ssize_t w = write(fds[1], text.data() + done, text.size() - done);
      if (w <= 0) _exit(1);
      done += static_cast<std::size_t>(w);
    }
    close(fds[1]);
    _exit(0);
  }
  close(fds[1]);
  std::string text;
  char buf[65536];
  for (;;) {
    const ssize_t n = read(fds[0], buf, sizeof buf);
    if (n > 0) {
      text.append(buf, static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  close(fds[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  MatchOutcome out;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    out.error = WIFSIGNALED(status)
                    ? "OpenCV's match crashed (signal " + std::to_string(WTERMSIG(status)) + ")"
                    : "the matching process failed";
    return out;
  }
  const json j = json::parse(text, nullptr, false);
  if (j.is_discarded()) {
    out.error = "the matching process sent no result";
    return out;
  }
  out.ms = j.at("ms").get<std::vector<double>>();
  out.poses = j.at("poses");
  out.error = j.at("error").get<std::string>();
  return out;
}

void check_options(const Options& o) {
  auto finite_in = [](double v, double lo, double hi) { return std::isfinite(v) && v > lo && v <= hi; };
  if (!finite_in(o.sampling, 1.0 / kMaxGridCells - 1e-12, 1.0))
    throw InputError("--sampling must be in [" + std::to_string(1.0 / kMaxGridCells) +
                     ", 1] (OpenCV: 1/sampling grid cells per axis)");
  if (!finite_in(o.distance_step, 0.0, 1.0)) throw InputError("--distance-step must be in (0, 1]");
  if (o.angles < 1 || o.angles > 360) throw InputError("--angles must be in [1, 360]");
  if (!finite_in(o.ref_ratio, 0.0, 1.0)) throw InputError("--ref-ratio must be in (0, 1]");
  if (o.scene_voxel_mm != -1 && !finite_in(o.scene_voxel_mm, 0.0, 1e6))
    throw InputError("--scene-voxel-mm must be a positive number of mm");
  if (o.position_threshold_mm != -1 && !finite_in(o.position_threshold_mm, 0.0, 1e9))
    throw InputError("--position-threshold-mm must be a positive number of mm");
  if (!finite_in(o.rotation_threshold_deg, 0.0, 180.0))
    throw InputError("--rotation-threshold-deg must be in (0, 180]");
  if (o.repeats < 1 || o.repeats > 1000) throw InputError("--repeats must be in [1, 1000]");
  if (o.top < 1 || o.top > 100000) throw InputError("--top must be in [1, 100000]");
}

std::vector<fs::path> list_crops(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir.string() + ": no such directory (--crops)");
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (e.is_regular_file() && name.starts_with("crop_") && name.ends_with(".ply"))
      files.push_back(e.path());
  }
  if (ec) throw InputError(dir.string() + ": cannot list: " + ec.message());
  if (files.empty()) throw InputError(dir.string() + ": no crop_*.ply files (--crops)");
  std::sort(files.begin(), files.end(),
            [](const fs::path& a, const fs::path& b) { return a.filename() < b.filename(); });
  return files;
}

void run(const Options& o) {
  check_options(o);
  const fs::path out_dir = o.out.has_parent_path() ? o.out.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(out_dir, ec))
    throw InputError(o.out.string() + ": the directory does not exist (--out)");
  const std::vector<fs::path> crop_files = list_crops(o.crops);
  // Read every crop before the (slow) training, so that a bad file fails at once.
  std::vector<cv::Mat> scenes;
  for (const fs::path& file : crop_files)
    scenes.push_back(to_mat(binpick::read_point_cloud_ply(file), file));

  const binpick::PointCloud model_cloud = binpick::read_point_cloud_ply(o.model);
  const cv::Mat model = to_mat(model_cloud, o.model);
  if (model.rows < 3) throw InputError(o.model.string() + ": fewer than 3 points");
  const Bbox mb = bbox_of(model);
  for (int k = 0; k < 3; ++k) {
    if (!(mb.extent(k) > 0))
      throw InputError(o.model.string() +
                       ": flat along an axis (OpenCV's sampling divides by each bbox extent)");
  }
  const int model_cells = opencv_grid_cells(o.sampling);
  const std::size_t model_sampled = opencv_sampled_count(model, mb, model_cells);
  if (model_sampled > kMaxModelPoints)
    throw InputError("OpenCV would keep " + std::to_string(model_sampled) +
                     " model points and store their n^2 pairs; use a larger --sampling");
  const double diag = mb.diagonal();
  const double voxel = o.scene_voxel_mm > 0 ? o.scene_voxel_mm : o.sampling * diag;
  const double pos_mm = o.position_threshold_mm > 0 ? o.position_threshold_mm : 0.144 * diag;
  const double rot_rad = o.rotation_threshold_deg * CV_PI / 180.0;
  const int k = reference_step(o.ref_ratio);
  const double sample_step = relative_scene_sample_step(k);

  // Train: a fresh detector per repeat (trainModel does not free a previous model).
  std::vector<double> train_ms;
  std::unique_ptr<Detector> det;
  for (int r = 0; r < o.repeats; ++r) {
    det = std::make_unique<Detector>(o.sampling, o.distance_step, static_cast<double>(o.angles));
    det->setSearchParams(pos_mm, rot_rad, false);
    const auto t0 = std::chrono::steady_clock::now();
    det->trainModel(model);
    train_ms.push_back(ms_since(t0));
  }

  json params = {
      {"sampling", o.sampling},
      {"distance_step", o.distance_step},
      {"angles", o.angles},
      {"ref_ratio", o.ref_ratio},
      {"scene_voxel_mm", voxel},
      {"position_threshold_mm", pos_mm},
      {"rotation_threshold_deg", o.rotation_threshold_deg},
      {"repeats", o.repeats},
      {"top", o.top},
      {"isolate", o.isolate},
      {"relativeSamplingStep", o.sampling},
      {"relativeDistanceStep", o.distance_step},
      {"numAngles", static_cast<double>(o.angles)},
      {"relativeSceneSampleStep", sample_step},
      {"reference_point_every", k},
      {"effective_ref_ratio", 1.0 / k},
      {"relativeSceneDistance", "per crop: crops[i].relativeSceneDistance"},
      {"positionThreshold", pos_mm},
      {"rotationThreshold_rad", rot_rad},
      {"useWeightedClustering", false},
      {"model_bbox_diagonal_mm", diag},
      {"opencv_model_grid_cells", model_cells},
      {"opencv_distance_step_mm", det->distance_step_used()},
      {"opencv_angle_step_rad", det->angle_step_used()},
  };
  json crops = json::array();
  for (std::size_t ci = 0; ci < crop_files.size(); ++ci) {
    const fs::path& file = crop_files[ci];
    const cv::Mat& scene = scenes[ci];
    json entry = {{"file", file.filename().string()}, {"points", scene.rows}};
    if (scene.rows == 0) {
      entry["ms"] = 0.0;
      entry["poses"] = json::array();
      entry["note"] = "empty crop";
      crops.push_back(entry);
      continue;
    }
    const Bbox b = bbox_of(scene);
    const SceneGrid g = scene_grid(b, voxel);
    entry["relativeSceneDistance"] = g.relative_distance;
    entry["opencv_grid_cells"] = g.cells;
    entry["opencv_cell_mm"] = {b.extent(0) / g.cells, b.extent(1) / g.cells, b.extent(2) / g.cells};
    if (!(b.extent(0) > 0 && b.extent(1) > 0 && b.extent(2) > 0)) {
      // OpenCV divides by each extent: 0/0 gives NaN cell indices (undefined behaviour).
      entry["ms"] = 0.0;
      entry["poses"] = json::array();
      entry["note"] = "flat along an axis: OpenCV's sampling cannot take it, not matched";
      crops.push_back(entry);
      continue;
    }
    const std::size_t sampled = opencv_sampled_count(scene, b, g.cells);
    entry["opencv_points"] = sampled;
    entry["opencv_reference_points"] = (sampled + k - 1) / k;
    entry["opencv_clustered_poses"] = sampled / k;  // match clusters only floor(n / k) poses
    const MatchOutcome m = o.isolate ? match_isolated(*det, scene, sample_step, g.relative_distance, o)
                                     : match_in_process(*det, scene, sample_step, g.relative_distance, o);
    entry["ms"] = median(m.ms);
    entry["poses"] = m.poses;
    if (!m.error.empty()) entry["error"] = m.error;
    crops.push_back(entry);
  }

  const json result = {{"opencv_version", CV_VERSION},
                       {"params", params},
                       {"model_input_points", model.rows},
                       {"model_points", det->model_points()},
                       {"train_ms", median(train_ms)},
                       {"crops", crops}};
  const std::string text = result.dump(1) + "\n";
  binpick::write_file_atomically(o.out, [&](std::ostream& s) { s.write(text.data(), text.size()); });
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{
      "opencv_ppf3d: OpenCV's PPF3DDetector (surface_matching) on binpick's crops, timed, for "
      "`binpick bench`. Trains on MODEL.ply, matches every DIR/crop_*.ply in name order and "
      "writes the poses and times as JSON."};
  app.add_option("--model", o.model, "model surface points, PLY with x y z nx ny nz (mm)")->required();
  app.add_option("--crops", o.crops, "directory of crop_NNNN.ply (camera frame, mm, with normals)")
      ->required();
  app.add_option("--out", o.out, "result JSON (written atomically)")->required();
  app.add_option("--sampling", o.sampling, "relativeSamplingStep of the model")->capture_default_str();
  app.add_option("--distance-step", o.distance_step,
                 "relativeDistanceStep (passed on; OpenCV ignores it and uses --sampling)")
      ->capture_default_str();
  app.add_option("--angles", o.angles, "numAngles")->capture_default_str();
  app.add_option("--ref-ratio", o.ref_ratio,
                 "share of the crop's points used as reference points (OpenCV: every round(1/r)-th)")
      ->capture_default_str();
  app.add_option("--scene-voxel-mm", o.scene_voxel_mm,
                 "voxel the crops were subsampled at; OpenCV's scene grid is sized to it "
                 "(default: sampling x model bbox diagonal)");
  app.add_option("--position-threshold-mm", o.position_threshold_mm,
                 "pose clustering translation threshold, mm (default: 0.144 x model bbox diagonal)");
  app.add_option("--rotation-threshold-deg", o.rotation_threshold_deg,
                 "pose clustering rotation threshold, degrees (OpenCV compares rotation angles only)")
      ->capture_default_str();
  app.add_option("--repeats", o.repeats, "timed runs of training and of each match (medians)")
      ->capture_default_str();
  app.add_option("--top", o.top, "poses kept per crop, most voted first")->capture_default_str();
  app.add_option("--isolate", o.isolate,
                 "match each crop in a forked process, so that a crash in OpenCV loses only that crop")
      ->capture_default_str();
  try {
    app.parse(argc, argv);
    run(o);
    return 0;
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const InputError& e) {
    std::cerr << "opencv_ppf3d: error: " << e.what() << "\n";
    return 2;
  } catch (const cv::Exception& e) {
    std::cerr << "opencv_ppf3d: OpenCV error: " << e.what() << "\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "opencv_ppf3d: internal error: " << e.what() << "\n";
    return 4;
  }
}
