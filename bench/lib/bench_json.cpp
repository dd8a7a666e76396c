// bench.json and the report files: every measured number under a stable key, so runs can be
// compared by script; the derived rates are included so no reader has to recompute them.
#include <fmt/format.h>

#include "bench/lib/bench_report.hpp"
#include "bench/lib/throughput.hpp"
#include "host/eval/report/gnuplot.hpp"
#include "host/core/atomic_file.hpp"

namespace binpick::bench {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json detect_json(const DetectMeasure& d, const MachineInfo& machine) {
  json stages = json::object();
  for (const auto& s : d.stages) stages[s.stage] = s.ms_per_hyp;
  const Throughput t = throughput(d, machine);
  return {{"ref_ratio", d.ref_ratio},
          {"hypotheses", d.hypotheses},
          {"images", d.images},
          {"ms_per_image", d.ms_per_image},
          {"ms_per_hypothesis",
           {{"preparation", d.prepare_ms}, {"hypotheses", d.hypotheses_ms}, {"voting", d.vote_ms},
            {"clustering", d.cluster_ms}, {"total", d.total_ms}}},
          {"stages_ms_per_hypothesis", stages},
          {"work_per_hypothesis",
           {{"pairs", d.counts.pairs}, {"lookups", d.counts.lookups}, {"votes", d.counts.votes},
            {"accumulator_cells", d.counts.cells}}},
          {"throughput",
           {{"pair_features_per_s", t.pairs_per_s}, {"lookups_per_s", t.lookups_per_s},
            {"votes_per_s", t.votes_per_s}, {"cells_per_s", t.cells_per_s},
            {"features_of_fma_peak", t.features_of_fma_peak},
            {"voting_of_gather_peak", t.voting_of_gather_peak},
            {"peaks_of_stream_peak", t.peaks_of_stream_peak},
            {"feature_flops_per_pair_estimate", kFeatureFlopsPerPair}}},
          {"precision",
           {{"top", d.precision_top}, {"all", d.precision_all},
            {"top_strict", d.precision_top_strict}, {"all_strict", d.precision_all_strict}}}};
}

json scaling_json(const Scaling& s) {
  json points = json::array();
  for (const auto& p : s.points)
    points.push_back({{"x", p.x}, {"size", p.size}, {"ms", p.ms}, {"extra", p.extra}});
  return {{"name", s.name}, {"x", s.x_label}, {"size", s.size_label}, {"exponent", s.exponent},
          {"points", points}};
}

json opencv_json(const OpenCvComparison& c) {
  json sides = json::array();
  for (const auto& s : c.sides)
    sides.push_back({{"ref_ratio", s.ref_ratio}, {"crops", s.crops},
                     {"binpick_ms_per_crop", s.binpick_ms}, {"opencv_ms_per_crop", s.opencv_ms},
                     {"opencv_over_binpick", s.binpick_ms > 0 ? s.opencv_ms / s.binpick_ms : 0.0},
                     {"binpick_precision", {{"top", s.binpick_top}, {"all", s.binpick_all}}},
                     {"opencv_precision", {{"top", s.opencv_top}, {"all", s.opencv_all}}}});
  return {{"ran", c.ran}, {"why_not", c.why_not}, {"version", c.version}, {"runner", c.runner},
          {"binpick_train_ms", c.binpick_train_ms}, {"opencv_train_ms", c.opencv_train_ms},
          {"sides", sides}};
}

// One log-log picture of the scaling sweeps: how cost grows is a slope to look at.
fs::path write_scaling_plot(const BenchResult& r, const fs::path& dir) {
  const auto gnuplot = eval::find_gnuplot();
  if (!gnuplot || r.scaling.empty()) return {};
  std::string script =
      "set terminal pngcairo size 1200,800 enhanced font 'DejaVu Sans,11'\n"
      "set logscale xy\nset grid\nset key top left\nset xlabel 'size (points)'\n"
      "set ylabel 'ms'\nset title 'binpick: time against size (log-log)'\n";
  std::string plot = "plot ";
  for (std::size_t i = 0; i < r.scaling.size(); ++i) {
    const auto& s = r.scaling[i];
    script += fmt::format("$d{} << EOD\n", i);
    for (const auto& p : s.points)
      if (p.size > 0 && p.ms > 0) script += fmt::format("{} {}\n", p.size, p.ms);
    script += "EOD\n";
    plot += fmt::format("{}$d{} with linespoints lw 2 title {}", i ? ", " : "", i,
                        eval::gnuplot_quoted(fmt::format("{} (k = {:.2f})", s.name, s.exponent)));
  }
  const fs::path png = dir / "scaling.png";
  eval::run_gnuplot_png(*gnuplot, script + plot + "\n", png);
  return png;
}

}  // namespace

json bench_json(const BenchResult& r) {
  const auto& m = r.machine;
  json j = {{"date", m.date},
            {"part", r.part},
            {"scene", r.scene},
            {"repeats", r.repeats},
            {"seconds", r.seconds},
            {"machine",
             {{"opencl", m.opencl}, {"vulkan", m.vulkan}, {"cores", m.cores},
              {"stream_gb_s", m.stream_gb_s}, {"fma_gflop_s", m.fma_gflop_s},
              {"gather_mlookup_s", m.gather_mlookup_s},
              {"gather_cached_mlookup_s", m.gather_cached_mlookup_s}, {"int_gop_s", m.int_gop_s}}},
            {"synth", json::array()},
            {"train",
             {{"voxel_ratio", r.train.voxel_ratio}, {"points", r.train.points},
              {"entries", r.train.entries}, {"ms", r.train.ms}}},
            {"detect", json::array()},
            {"scaling", json::array()},
            {"opencv", opencv_json(r.opencv)}};
  for (const auto& b : r.synth)
    j["synth"].push_back({{"bin", b.bin}, {"physics_s", b.physics_s}, {"render_s", b.render_s},
                          {"decompose_s", b.decompose_s}, {"write_s", b.write_s},
                          {"measured_now", b.measured_now}});
  for (const auto& d : r.detect) j["detect"].push_back(detect_json(d, m));
  if (r.real) j["real_size"] = {{"scene", r.real_scene}, {"detect", detect_json(*r.real, m)}};
  for (const auto& s : r.scaling) j["scaling"].push_back(scaling_json(s));
  return j;
}

BenchFiles write_bench_report(const BenchResult& r, const fs::path& dir) {
  fs::create_directories(dir);
  BenchFiles files{dir / "bench.md", dir / "bench.json", {}};
  write_file_atomically(files.json, [&](std::ostream& os) { os << bench_json(r).dump(2) << "\n"; });
  try {
    files.plot = write_scaling_plot(r, dir);
  } catch (const std::exception&) {
    files.plot.clear();  // the tables carry the same numbers; a picture is a convenience
  }
  std::string md = bench_markdown(r);
  if (!files.plot.empty()) md += "\n![scaling](scaling.png)\n";
  write_file_atomically(files.markdown, [&](std::ostream& os) { os << md; });
  return files;
}

}  // namespace binpick::bench
