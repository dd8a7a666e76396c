#include "bench/lib/stage_bench.hpp"

#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "bench/lib/pair_counts.hpp"
#include "host/formats/bop/bop_files.hpp"
#include "host/formats/bop/png_image.hpp"
#include "host/detect/batch/detect_batch.hpp"
#include "host/eval/metrics/evaluate.hpp"

namespace binpick::bench {
namespace fs = std::filesystem;

namespace {

// The stages of DetectTimes::stages in the four groups of the paper's timing.
bool is_vote_stage(const std::string& s) { return s == "features" || s == "vote" || s == "peaks"; }
bool is_cluster_stage(const std::string& s) { return s == "poses" || s == "cluster"; }

struct Repetition {
  std::vector<std::string> order;        // stage names, first appearance
  std::map<std::string, double> ms;      // summed over the images
  std::size_t hypotheses = 0;
};

void add(Repetition& rep, const DetectTimes& t) {
  for (const auto& s : t.stages) {
    if (!rep.ms.count(s.stage)) rep.order.push_back(s.stage);
    rep.ms[s.stage] += s.ms;
  }
  rep.hypotheses += t.hypotheses;
}

double group_ms(const Repetition& r, bool (*in)(const std::string&)) {
  double ms = 0;
  for (const auto& [stage, v] : r.ms)
    if (in(stage)) ms += v;
  return ms;
}

}  // namespace

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::vector<BenchScene> load_bench_scenes(const fs::path& dataset) {
  std::vector<BenchScene> scenes;
  for (int id : list_scenes(dataset, "test")) {
    const fs::path dir = dataset / "test" / fmt::format("{:06d}", id);
    const auto png = read_png16(dir / "depth" / "000000.png");
    const auto cam = bop::read_scene_cameras(dir / "scene_camera.json").at(0);
    BenchScene s;
    s.scene_id = id;
    s.depth = {png.width, png.height, png.pixels};
    s.camera = image_camera(cam.K, cam.depth_scale, png.width, png.height);
    scenes.push_back(std::move(s));
  }
  return scenes;
}

Precision precision_of(const eval::Dataset& dataset, const std::vector<bop::ResultRow>& rows) {
  const eval::EvalSummary s = eval::evaluate(dataset, rows);
  return {s.loose.top, s.loose.all, s.strict.top, s.strict.all};
}

StageRun run_stages(const PpfModel& model, const DetectParams& params,
                    const std::vector<BenchScene>& scenes, const eval::Dataset& dataset,
                    int repeats) {
  StageRun run;
  Detector detector(model, params);
  if (!scenes.empty()) (void)detector.detect(scenes[0].depth, scenes[0].camera);  // warm-up
  std::vector<Repetition> reps(std::size_t(std::max(repeats, 1)));
  for (std::size_t r = 0; r < reps.size(); ++r) {
    for (const BenchScene& scene : scenes) {
      DetectTimes t;
      std::vector<PointCloud> clouds;
      const auto found = detector.detect(scene.depth, scene.camera, &t, r == 0 ? &clouds : nullptr);
      add(reps[r], t);
      if (r != 0) continue;
      const double seconds = t.total_ms() / 1e3;
      const auto rows = detection_rows(found, scene.scene_id, 0, 1, seconds);
      run.rows.insert(run.rows.end(), rows.begin(), rows.end());
      for (std::size_t k = 0; k < clouds.size(); ++k) {
        BenchCrop c;
        c.scene_id = scene.scene_id;
        c.hypothesis = std::uint32_t(k);
        c.cloud = std::move(clouds[k]);
        for (const Detection& d : found)
          if (d.index == k) c.detection = d;
        run.crops.push_back(std::move(c));
      }
    }
  }

  DetectMeasure& m = run.measure;
  m.ref_ratio = params.ref_ratio;
  m.hypotheses = reps[0].hypotheses;
  const double h = double(std::max<std::size_t>(m.hypotheses, 1));
  auto per_hyp = [&](auto value) {
    std::vector<double> v;
    for (const Repetition& r : reps) v.push_back(value(r) / h);
    return median(v);
  };
  auto stage = [](const char* name) {
    return [name](const Repetition& r) { return r.ms.count(name) ? r.ms.at(name) : 0.0; };
  };
  m.hypotheses_ms = per_hyp(stage("hypotheses"));
  m.vote_ms = per_hyp([](const Repetition& r) { return group_ms(r, is_vote_stage); });
  m.cluster_ms = per_hyp([](const Repetition& r) { return group_ms(r, is_cluster_stage); });
  m.prepare_ms = per_hyp([](const Repetition& r) {
    double ms = 0;
    for (const auto& [s, v] : r.ms)
      if (!is_vote_stage(s) && !is_cluster_stage(s) && s != "hypotheses") ms += v;
    return ms;
  });
  auto all_stages = [](const Repetition& r) {
    double ms = 0;
    for (const auto& [s, v] : r.ms) ms += v;
    return ms;
  };
  m.total_ms = per_hyp(all_stages);
  m.images = scenes.size();
  std::vector<double> per_image;
  for (const Repetition& r : reps) per_image.push_back(all_stages(r) / double(std::max<std::size_t>(m.images, 1)));
  m.ms_per_image = median(per_image);
  m.features_ms = per_hyp(stage("features"));
  m.votes_ms = per_hyp(stage("vote"));
  m.peaks_ms = per_hyp(stage("peaks"));
  for (const std::string& name : reps[0].order) m.stages.push_back({name, per_hyp(stage(name.c_str()))});

  for (const BenchCrop& c : run.crops) m.counts += count_pairs(c.cloud, params.ref_ratio, model);
  m.counts.pairs /= h, m.counts.lookups /= h, m.counts.votes /= h, m.counts.cells /= h;

  const Precision p = precision_of(dataset, run.rows);
  m.precision_top = p.top, m.precision_all = p.all;
  m.precision_top_strict = p.top_strict, m.precision_all_strict = p.all_strict;
  return run;
}

}  // namespace binpick::bench
