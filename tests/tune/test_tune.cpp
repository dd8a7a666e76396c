// `binpick tune`: the search on its own (a made-up measure: it finds the optimum, respects the
// budget and max-evals, never measures a point twice, is deterministic), and the verb as a user
// runs it: from a deliberately bad start it finds strictly better precision, prints and writes
// the table, writes best.json that detect accepts and the matching model, and a rerun resumes
// to the same table. Bad options exit 2 with one message.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/detect/params/params_file.hpp"
#include "host/train/ppf_model_file.hpp"
#include "host/tune/tune_search.hpp"
#include "tests/support/cli_run.hpp"

using namespace binpick;
namespace fs = std::filesystem;

namespace {

// A separable made-up objective: precision is highest at ref-ratio 0.1, cluster distance 0.25,
// cluster angle 10, exclusion 1.5, 45 angle steps and 10 distance steps; time grows with the
// reference ratio.
TuneScore made_up(const TunePoint& p) {
  double miss = std::abs(p.detect.ref_ratio - 0.1) + std::abs(p.detect.cluster_distance - 0.25) +
                std::abs(p.detect.cluster_angle - 10) / 100 +
                std::abs(p.detect.exclusion_ratio - 1.5) + std::abs(double(p.angle_steps) - 45) / 100 +
                std::abs(double(p.distance_steps) - 10) / 100;
  TuneScore s;
  s.top = 1 / (1 + miss);
  s.all = s.top / 2;
  s.strict_top = s.top / 3;
  s.ms_per_hypothesis = 1000 * p.detect.ref_ratio;
  return s;
}

}  // namespace

TEST(TuneObjective, BudgetFirstThenTopThenStrictThenAllThenTime) {
  const double budget = 100;
  TuneScore a{0.5, 0.5, 0.5, 0.5, 50}, b = a;
  b.ms_per_hypothesis = 150;  // over the budget
  EXPECT_TRUE(better(a, b, budget));
  EXPECT_FALSE(better(b, a, budget));
  b = a;
  b.top = 0.6;
  EXPECT_TRUE(better(b, a, budget));
  b = a;
  b.strict_top = 0.6;
  EXPECT_TRUE(better(b, a, budget));
  b = a;
  b.all = 0.6;  // the top-voted tie: all hypotheses decide
  EXPECT_TRUE(better(b, a, budget));
  b = a;
  b.strict_all = 0.6;
  EXPECT_TRUE(better(b, a, budget));
  b = a;
  b.ms_per_hypothesis = 40;
  EXPECT_TRUE(better(b, a, budget));
  b.ms_per_hypothesis = 49;  // within the noise of a measured time
  EXPECT_FALSE(better(b, a, budget));
  EXPECT_FALSE(better(a, b, budget));
  EXPECT_FALSE(better(a, a, budget));  // strictly
  TuneScore slow{1, 1, 1, 1, 300}, slower{1, 1, 1, 1, 400};
  EXPECT_TRUE(better(slow, slower, budget));  // nothing fits: the least over
}

TEST(TuneSearch, FindsTheOptimumMeasuringEachPointOnceDeterministically) {
  SearchOptions o;
  o.budget_ms = 1e9;
  o.rounds = 3;
  o.max_evals = 1000;
  TunePoint start;  // the paper's parameters
  std::vector<std::string> seen;
  const auto measure = [&](const TunePoint& p) {
    seen.push_back(point_key(p));
    return made_up(p);
  };
  const SearchResult r = coordinate_descent(start, o, measure);
  const TunePoint& best = r.rows[r.best].point;
  EXPECT_DOUBLE_EQ(best.detect.ref_ratio, 0.1);
  EXPECT_DOUBLE_EQ(best.detect.cluster_distance, 0.25);
  EXPECT_DOUBLE_EQ(best.detect.cluster_angle, 10);
  EXPECT_DOUBLE_EQ(best.detect.exclusion_ratio, 1.5);
  EXPECT_EQ(best.angle_steps, 45u);
  EXPECT_EQ(best.distance_steps, 10u);
  EXPECT_EQ(std::set<std::string>(seen.begin(), seen.end()).size(), seen.size());
  EXPECT_EQ(r.rows.size(), seen.size());
  EXPECT_EQ(r.rows[0].axis, "start");
  EXPECT_EQ(point_key(r.rows[0].point), point_key(start));
  EXPECT_LE(r.rows.size(), max_measurements(o));

  const SearchResult again = coordinate_descent(start, o, made_up);
  ASSERT_EQ(again.rows.size(), r.rows.size());
  EXPECT_EQ(again.best, r.best);
  for (std::size_t i = 0; i < r.rows.size(); ++i)
    EXPECT_EQ(point_key(again.rows[i].point), point_key(r.rows[i].point));
}

TEST(TuneSearch, KeepsToTheBudgetAndToMaxEvals) {
  SearchOptions o;
  o.budget_ms = 60;  // made_up's time is 1000 x ref-ratio: 0.1 does not fit, 0.05 does
  o.rounds = 2;
  o.max_evals = 1000;
  const SearchResult r = coordinate_descent(TunePoint{}, o, made_up);
  EXPECT_TRUE(r.rows[r.best].within_budget);
  EXPECT_DOUBLE_EQ(r.rows[r.best].point.detect.ref_ratio, 0.05);

  o.max_evals = 4;
  std::size_t calls = 0;
  const SearchResult few = coordinate_descent(
      TunePoint{}, o, made_up, [&](const TuneRow& row, std::size_t best) {
        EXPECT_EQ(row.index, calls++);
        EXPECT_LE(best, row.index);
      });
  EXPECT_EQ(few.rows.size(), 4u);
  EXPECT_EQ(calls, 4u);
}

TEST(TuneSearch, RejectsBadOptions) {
  SearchOptions o;
  o.budget_ms = -1;
  EXPECT_THROW(check(o), InputError);
  o.budget_ms = 10;
  o.rounds = 0;
  EXPECT_THROW(check(o), InputError);
  o.rounds = 1;
  o.max_evals = 0;
  EXPECT_THROW(check(o), InputError);
}

namespace {

struct CsvRow {
  std::size_t index = 0;
  double top = 0, all = 0, strict_top = 0, ms = 0;
  bool best = false;
};

std::vector<CsvRow> read_tune_csv(const fs::path& path) {
  std::istringstream in(test::slurp(path));
  std::string line;
  std::getline(in, line);  // header
  std::vector<CsvRow> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ls(line);
    for (std::string item; std::getline(ls, item, ',');) f.push_back(item);
    EXPECT_EQ(f.size(), 16u) << line;
    if (f.size() != 16) continue;
    rows.push_back({std::stoul(f[0]), std::stod(f[9]), std::stod(f[10]), std::stod(f[11]),
                    std::stod(f[13]), f[15] == "1"});
  }
  return rows;
}

}  // namespace

// The start votes with almost no reference points and clusters nothing: the first axis
// (reference ratio) already finds better precision, so three measurements are enough.
TEST(TuneCli, ImprovesOnABadStartWritesBestAndResumes) {
  const fs::path dir = test::fresh_temp_dir("tune_cli");
  const std::string cmd = fmt::format(
      "tune --model builtin:bracket --out {} --bins 2 --objects 25 --width 640 --height 360 "
      "--budget-ms 1000000 --max-evals 3 --ref-ratio 0.002 --cluster-angle 2 "
      "--cluster-distance 0.01",
      (dir / "t").string());
  auto r = test::run_binpick(cmd);
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("<- best"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("best.json"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--distance-steps 20 --angle-steps 30"), std::string::npos) << r.out;

  const auto rows = read_tune_csv(dir / "t" / "tune.csv");
  ASSERT_EQ(rows.size(), 3u);
  const CsvRow& start = rows[0];
  std::size_t best = 0;
  for (const auto& row : rows)
    if (row.best) best = row.index;
  ASSERT_NE(best, 0u) << r.out;
  // Better by tune's own objective, time aside: top-voted precision, then strict top-voted,
  // then all hypotheses. Two bins make top precision coarse (0, 50 or 100 %), so a tie there
  // is common and the later criteria decide.
  const CsvRow& b = rows[best];
  const bool more_precise =
      b.top > start.top || (b.top == start.top && b.strict_top > start.strict_top) ||
      (b.top == start.top && b.strict_top == start.strict_top && b.all > start.all);
  EXPECT_TRUE(more_precise) << r.out;

  // best.json is what detect --params reads; best.ppfm is a model of the best point's steps.
  DetectParams p;
  apply_params_file(dir / "t" / "best.json", p);
  EXPECT_NE(p.ref_ratio, 0.002);
  EXPECT_DOUBLE_EQ(p.cluster_angle, 2);
  const PpfModel model = read_ppf_model(dir / "t" / "best.ppfm");
  EXPECT_EQ(model.quant.n_dist, 20u);
  EXPECT_TRUE(fs::is_regular_file(dir / "t" / "best-train.json"));

  // Again: everything is reused, the table is the same, to the byte (times come from the
  // results kept).
  const std::string table = test::slurp(dir / "t" / "tune.csv");
  const auto t0 = std::chrono::steady_clock::now();
  r = test::run_binpick(cmd);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(test::slurp(dir / "t" / "tune.csv"), table);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 30.0);
  fs::remove_all(dir);
}

TEST(TuneCli, BadOptionsExit2WithOneMessage) {
  const fs::path dir = test::fresh_temp_dir("tune_bad");
  const std::string out = (dir / "t").string();
  for (const std::string args :
       {"--model builtin:bracket --budget-ms -5", "--model builtin:nosuch",
        "--model builtin:bracket --rounds 0", "--model builtin:bracket --ref-ratio 0",
        "--model builtin:bracket --angle-steps 2", "--model builtin:bracket --bins 0"}) {
    const auto r = test::run_binpick("tune " + args + " --out " + out);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find("binpick: error: "), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
  }
  EXPECT_FALSE(fs::exists(out));  // nothing made for bad options
  fs::remove_all(dir);
}
