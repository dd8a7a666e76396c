// The benchmark's arithmetic and report (bench/lib/): the log-log exponent, the throughput
// fractions, the pair counts against a brute-force count, and the tables and JSON keys a
// reader and a script rely on.
#include <gtest/gtest.h>

#include <cmath>

#include "bench/lib/bench_report.hpp"
#include "bench/lib/pair_counts.hpp"
#include "bench/lib/scaling_bench.hpp"
#include "bench/lib/throughput.hpp"
#include "host/detect/vote/ppf_vote.hpp"
#include "host/app/options/model_options.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "host/train/ppf_features.hpp"

using namespace binpick;
using namespace binpick::bench;

TEST(BenchScaling, log_log_slope_recovers_a_power_law) {
  std::vector<ScalingPoint> pts;
  for (double n : {100.0, 200.0, 400.0, 1600.0}) pts.push_back({0, n, 3e-4 * std::pow(n, 1.7), 0});
  EXPECT_NEAR(log_log_slope(pts), 1.7, 1e-9);
  pts.push_back({0, 0, 5, 0});  // sizes or times that are not positive are left out
  pts.push_back({0, 10, 0, 0});
  EXPECT_NEAR(log_log_slope(pts), 1.7, 1e-9);
}

TEST(BenchScaling, log_log_slope_of_too_few_points_is_zero) {
  EXPECT_EQ(log_log_slope({}), 0.0);
  EXPECT_EQ(log_log_slope({{0, 100, 1, 0}}), 0.0);
  EXPECT_EQ(log_log_slope({{0, 100, 1, 0}, {0, 100, 2, 0}}), 0.0);  // one size twice
}

TEST(BenchMedian, odd_even_and_empty) {
  EXPECT_EQ(median({3, 1, 2}), 2);
  EXPECT_EQ(median({4, 1, 3, 2}), 2.5);
  EXPECT_EQ(median({}), 0);
}

TEST(BenchThroughput, rates_and_fractions_of_the_peaks) {
  DetectMeasure m;
  m.counts.pairs = 1e6, m.counts.lookups = 5e5, m.counts.votes = 2e6, m.counts.cells = 4e6;
  m.features_ms = 10, m.votes_ms = 20, m.peaks_ms = 2;
  MachineInfo machine;
  machine.fma_gflop_s = 100, machine.gather_cached_mlookup_s = 500, machine.stream_gb_s = 16;
  const Throughput t = throughput(m, machine);
  EXPECT_DOUBLE_EQ(t.pairs_per_s, 1e8);
  EXPECT_DOUBLE_EQ(t.lookups_per_s, 2.5e7);
  EXPECT_DOUBLE_EQ(t.votes_per_s, 1e8);
  EXPECT_DOUBLE_EQ(t.cells_per_s, 2e9);
  EXPECT_DOUBLE_EQ(t.features_of_fma_peak, 1e8 * kFeatureFlopsPerPair / 1e11);
  EXPECT_DOUBLE_EQ(t.voting_of_gather_peak, 1.25e8 / 5e8);
  EXPECT_DOUBLE_EQ(t.peaks_of_stream_peak, 8e9 / 16e9);
  const Throughput none = throughput(DetectMeasure{}, MachineInfo{});  // no time, no peak
  EXPECT_EQ(none.pairs_per_s, 0);
  EXPECT_EQ(none.features_of_fma_peak, 0);
}

TEST(BenchPairCounts, equal_a_brute_force_count_over_the_table) {
  const Mesh mesh = cli::load_part({"builtin:bolt", {}}).mesh;
  const PpfModel model = train_ppf_model(mesh, {});
  // The model's own points as the scene: every pair within the diameter has a key.
  const PointCloud& scene = model.cloud;
  const double ratio = 0.1;
  const PairCounts c = count_pairs(scene, ratio, model);
  const auto refs = select_reference_points(scene.points.size(), ratio);
  double lookups = 0, votes = 0;
  for (std::uint32_t r : refs)
    for (std::size_t i = 0; i < scene.points.size(); ++i) {
      if (i == r) continue;
      const std::uint32_t key = ppf_pair_feature_reference(scene.points[r], scene.normals[r],
                                                           scene.points[i], scene.normals[i],
                                                           model.quant).key;
      if (key == BP_PPF_NO_KEY) continue;
      lookups += 1;
      votes += model.table.offsets[key + 1] - model.table.offsets[key];
    }
  EXPECT_EQ(c.pairs, double(refs.size() * scene.points.size()));
  EXPECT_EQ(c.lookups, lookups);
  EXPECT_EQ(c.votes, votes);
  EXPECT_GT(c.votes, c.lookups);  // the model's own pairs are all in its table
  EXPECT_EQ(c.cells, double(refs.size()) * scene.points.size() * model.quant.n_alpha);
  EXPECT_EQ(count_pairs(PointCloud{}, ratio, model).pairs, 0);
}

namespace {

BenchResult sample_result() {
  BenchResult r;
  r.part = "builtin:bracket";
  r.scene = "1600 x 900, 350 parts, 3 bins";
  r.repeats = 3;
  r.machine.opencl = "pthread-cpu";
  r.machine.stream_gb_s = 10, r.machine.fma_gflop_s = 50, r.machine.gather_mlookup_s = 300;
  r.synth = {{0, 17.5, 0.9, 0.001, 0.3, true}, {1, -1, -1, -1, -1, false}};
  r.train = {0.05, 439, 192282, 94};
  DetectMeasure d;
  d.ref_ratio = 0.2;
  d.hypotheses = 15;
  d.total_ms = 37.25;
  d.stages = {{"points", 1.0}, {"prerank (10 highest points)", 3.0}, {"vote", 20.0}};
  d.images = 3;
  d.ms_per_image = 186.25;
  r.detect = {d};
  DetectMeasure real = d;  // 5 hypotheses an image: per image = per hypothesis x 5
  real.hypotheses = 10;
  real.images = 2;
  real.ms_per_image = 412.5;
  real.total_ms = 82.5;
  real.stages = {{"points", 4.0}, {"prerank (8 highest points)", 2.0}, {"vote", 60.0}};
  r.real = real;
  r.real_scene = "2064 x 1544, structured light, 2 m, tilted 20°";
  r.scaling = {{"voting vs reference points", "reference ratio", "reference points",
                {{0.1, 50, 2, 0}, {0.2, 100, 4, 0}}, 1.0}};
  r.opencv.why_not = "opencv_ppf3d was not built";
  return r;
}

}  // namespace

TEST(BenchReport, markdown_has_every_table) {
  const std::string md = bench_markdown(sample_result());
  for (const char* want :
       {"## Detection, ms per hypothesis", "| 20 % | 15 |", "**37.25**", "| 726 |",
        "## Throughput against the machine", "## Synthetic bins", "| 0 | 17.5 |",
        "made by an earlier run without a record", "## Model", "192282 table entries",
        "## Scaling", "(k = 1.00: about linear)", "## OpenCV's PPF3DDetector side by side",
        "Not run: opencv_ppf3d was not built", "| vote | 20.000 |",
        "The limit at 20 % reference points: vote, 20.0 of 37.2 ms a hypothesis (54 %).",
        "## The real sensor's size",
        "| 1600 x 900, 350 parts, 3 bins | 20 % | 5.0 | **186** | 37.2 |",
        "| 2064 x 1544, structured light, 2 m, tilted 20° | 20 % | 5.0 | **412** | 82.5 |",
        // per image: the paper's 1.0 x 15 / 3, the real 4.0 x 10 / 2; the prerank matched by name
        "| points | 5.0 | 20.0 |", "| prerank (8 highest points) | 15.0 | 10.0 |",
        "| vote | 100.0 | 300.0 |"})
    EXPECT_NE(md.find(want), std::string::npos) << want << "\n" << md;
}

TEST(BenchReport, json_keys_for_scripts) {
  const auto j = bench_json(sample_result());
  EXPECT_EQ(j.at("detect").at(0).at("ms_per_hypothesis").at("total"), 37.25);
  EXPECT_EQ(j.at("detect").at(0).at("stages_ms_per_hypothesis").at("vote"), 20.0);
  EXPECT_TRUE(j.at("detect").at(0).at("throughput").contains("features_of_fma_peak"));
  EXPECT_EQ(j.at("train").at("entries"), 192282);
  EXPECT_EQ(j.at("synth").size(), 2u);
  EXPECT_EQ(j.at("scaling").at(0).at("exponent"), 1.0);
  EXPECT_FALSE(j.at("opencv").at("ran").get<bool>());
  EXPECT_EQ(j.at("machine").at("gather_mlookup_s"), 300);
  EXPECT_EQ(j.at("detect").at(0).at("ms_per_image"), 186.25);
  EXPECT_EQ(j.at("real_size").at("detect").at("ms_per_image"), 412.5);
  EXPECT_EQ(j.at("real_size").at("detect").at("images"), 2);
  BenchResult without = sample_result();
  without.real.reset();
  EXPECT_FALSE(bench_json(without).contains("real_size"));
  EXPECT_EQ(bench_markdown(without).find("real sensor"), std::string::npos);
}
