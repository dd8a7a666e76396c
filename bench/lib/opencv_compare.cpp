#include "bench/lib/opencv_compare.hpp"

#include <unistd.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "bench/lib/subprocess.hpp"
#include "host/core/error.hpp"
#include "host/formats/mesh/point_cloud_ply.hpp"
#include "host/core/read_file.hpp"

namespace binpick::bench {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

fs::path own_directory() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : self.parent_path();
}

std::string crop_name(std::size_t i) { return fmt::format("crop_{:04d}.ply", i); }

// binpick's side: each crop voted on alone (the same call the stage run made inside detect),
// timed over the repetitions; one result row per crop.
std::vector<bop::ResultRow> binpick_side(const PpfModel& model, const DetectParams& params,
                                         const std::vector<BenchCrop>& crops, int repeats,
                                         double* ms_per_crop) {
  Detector detector(model, params);
  if (!crops.empty()) (void)detector.detect_subsampled(crops[0].cloud);  // warm-up
  std::vector<bop::ResultRow> rows;
  std::vector<double> per_rep;
  for (int r = 0; r < repeats; ++r) {
    DetectTimes t;
    for (const BenchCrop& c : crops) {
      const Detection d = detector.detect_subsampled(c.cloud, &t);
      if (r > 0) continue;
      bop::ResultRow row;
      row.scene_id = c.scene_id;
      row.score = double(d.votes);
      row.R = d.R;
      row.t = d.t;
      if (d.votes > 0) rows.push_back(row);
    }
    per_rep.push_back((t.vote_ms + t.cluster_ms) / double(std::max<std::size_t>(crops.size(), 1)));
  }
  *ms_per_crop = median(per_rep);
  return rows;
}

// OpenCV's side from the runner's JSON: its best pose per crop.
std::vector<bop::ResultRow> opencv_rows(const json& result, const std::vector<BenchCrop>& crops,
                                        double* ms_per_crop) {
  std::vector<bop::ResultRow> rows;
  std::vector<double> ms;
  const auto& list = result.at("crops");
  if (list.size() != crops.size())
    throw InputError(fmt::format("opencv_ppf3d returned {} crops for {}", list.size(), crops.size()));
  for (std::size_t i = 0; i < crops.size(); ++i) {
    const json& c = list[i];
    ms.push_back(c.at("ms").get<double>());
    if (c.at("poses").empty()) continue;
    const json& p = c.at("poses")[0];
    bop::ResultRow row;
    row.scene_id = crops[i].scene_id;
    row.score = p.at("votes").get<double>();
    for (int k = 0; k < 9; ++k) row.R(k / 3, k % 3) = p.at("R")[k].get<double>();
    for (int k = 0; k < 3; ++k) row.t(k) = p.at("t")[k].get<double>();
    rows.push_back(row);
  }
  double sum = 0;
  for (double m : ms) sum += m;
  *ms_per_crop = ms.empty() ? 0 : sum / double(ms.size());
  return rows;
}

}  // namespace

fs::path find_opencv_runner(const std::string& option, std::string* why) {
  if (option == "off") {
    *why = "turned off (--opencv off)";
    return {};
  }
  const fs::path runner = option == "auto" ? own_directory() / "opencv_ppf3d" : fs::path(option);
  if (::access(runner.c_str(), X_OK) == 0) return runner;
  *why = option == "auto"
             ? "opencv_ppf3d was not built (install Debian's libopencv-contrib-dev and rebuild; "
               "./run.sh bench does both)"
             : "--opencv " + option + " is not an executable file";
  return {};
}

OpenCvComparison compare_with_opencv(const PpfModel& model, const BenchOptions& o,
                                     const std::vector<BenchCrop>& crops,
                                     const eval::Dataset& dataset, double binpick_train_ms) {
  OpenCvComparison cmp;
  const fs::path runner = find_opencv_runner(o.opencv, &cmp.why_not);
  if (runner.empty()) return cmp;
  cmp.runner = runner.string();
  cmp.binpick_train_ms = binpick_train_ms;

  const fs::path dir = o.out / "opencv";
  const fs::path crop_dir = dir / "crops";
  fs::remove_all(crop_dir);
  fs::create_directories(crop_dir);
  write_point_cloud_ply(dir / "model.ply", model.cloud);
  for (std::size_t i = 0; i < crops.size(); ++i)
    write_point_cloud_ply(crop_dir / crop_name(i), crops[i].cloud);

  for (double ratio : o.ref_ratios) {
    const fs::path out = dir / fmt::format("opencv_ref_{:g}.json", ratio * 100);
    fs::remove(out);
    const std::vector<std::string> args{
        "--model", (dir / "model.ply").string(), "--crops", crop_dir.string(), "--out",
        out.string(), "--sampling", fmt::format("{}", o.train.voxel_ratio), "--distance-step",
        fmt::format("{}", 1.0 / o.train.distance_steps), "--angles",
        std::to_string(o.train.angle_steps), "--ref-ratio", fmt::format("{}", ratio),
        "--scene-voxel-mm", fmt::format("{}", model.voxel_size), "--position-threshold-mm",
        fmt::format("{}", o.detect.cluster_distance * model.diameter), "--rotation-threshold-deg",
        fmt::format("{}", o.detect.cluster_angle), "--repeats", std::to_string(o.repeats)};
    const int status = run_program(runner.string(), args);
    if (status != 0 || !fs::exists(out)) {
      cmp.why_not = fmt::format("{} failed (exit status {}); its message is above", runner.string(),
                                status);
      cmp.sides.clear();
      return cmp;
    }
    const json result = json::parse(read_file_bytes(out));
    cmp.version = result.value("opencv_version", "");
    cmp.opencv_train_ms = result.value("train_ms", 0.0);

    OpenCvSide side;
    side.ref_ratio = ratio;
    side.crops = crops.size();
    DetectParams p = o.detect;
    p.ref_ratio = ratio;
    const auto ours = binpick_side(model, p, crops, o.repeats, &side.binpick_ms);
    const auto theirs = opencv_rows(result, crops, &side.opencv_ms);
    const Precision a = precision_of(dataset, ours), b = precision_of(dataset, theirs);
    // "all" over the crops, not over the poses returned: a crop without a pose is a miss.
    const double n = double(std::max<std::size_t>(crops.size(), 1));
    side.binpick_top = a.top, side.binpick_all = a.all * double(ours.size()) / n;
    side.opencv_top = b.top, side.opencv_all = b.all * double(theirs.size()) / n;
    cmp.sides.push_back(side);
  }
  cmp.ran = true;
  cmp.why_not.clear();
  return cmp;
}

}  // namespace binpick::bench
