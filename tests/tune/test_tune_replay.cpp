// `tune --slurm`'s pieces that need no cluster: the search replayed over measurements made in
// batches elsewhere ends with exactly the rows a single process measures, each batch holding only
// unmeasured points, the first one the start and its round; the candidates file round-trips the
// points and refuses a task started with other options or a damaged file.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>

#include "host/core/error.hpp"
#include "host/tune/tune_candidates.hpp"
#include "host/tune/tune_replay.hpp"
#include "tests/support/cli_run.hpp"

using namespace binpick;
namespace fs = std::filesystem;

namespace {

// Made up, with a moving optimum so that the anchor moves within rounds: best at ref-ratio 0.05,
// cluster angle 30 and 45 angle steps; time grows with the reference ratio.
TuneScore made_up(const TunePoint& p) {
  const double miss = std::abs(p.detect.ref_ratio - 0.05) + std::abs(p.detect.cluster_angle - 30) / 100 +
                      std::abs(double(p.angle_steps) - 45) / 100;
  return {1 / (1 + miss), 0.5 / (1 + miss), 0.3 / (1 + miss), 0.1, 100 * p.detect.ref_ratio};
}

// Replays, "measuring" each batch, until the search is whole; returns it and the batches.
SearchResult replay_to_the_end(const TunePoint& start, const SearchOptions& o,
                               std::vector<std::vector<TunePoint>>& batches) {
  std::map<std::string, TuneScore> measured;
  const LookupFn lookup = [&](const TunePoint& p) -> std::optional<TuneScore> {
    const auto it = measured.find(point_key(p));
    if (it == measured.end()) return std::nullopt;
    return it->second;
  };
  for (int guard = 0; guard < 1000; ++guard) {
    SearchReplay r = replay_search(start, o, lookup);
    if (r.result) return *r.result;
    EXPECT_FALSE(r.next.empty());
    for (const TunePoint& p : r.next) {
      EXPECT_FALSE(lookup(p)) << "a batch holds a measured point";
      measured[point_key(p)] = made_up(p);
    }
    batches.push_back(r.next);
  }
  ADD_FAILURE() << "the replay never ended";
  return {};
}

}  // namespace

TEST(TuneReplay, BatchesGiveTheSingleProcessRows) {
  for (int max_evals : {1, 3, 12, 40}) {
    SearchOptions o;
    o.budget_ms = 1e9;
    o.rounds = 3;
    o.max_evals = max_evals;
    const TunePoint start;
    const SearchResult direct = coordinate_descent(start, o, made_up);
    std::vector<std::vector<TunePoint>> batches;
    const SearchResult replayed = replay_to_the_end(start, o, batches);
    ASSERT_EQ(replayed.rows.size(), direct.rows.size()) << "max_evals " << max_evals;
    for (std::size_t i = 0; i < direct.rows.size(); ++i) {
      EXPECT_TRUE(same_point(replayed.rows[i].point, direct.rows[i].point));
      EXPECT_EQ(replayed.rows[i].axis, direct.rows[i].axis);
      EXPECT_EQ(replayed.rows[i].score.top, direct.rows[i].score.top);
    }
    EXPECT_EQ(replayed.best, direct.best);
    ASSERT_FALSE(batches.empty());
    EXPECT_TRUE(same_point(batches[0][0], start));  // the start first
    std::size_t total = 0;
    for (const auto& b : batches) total += b.size();
    EXPECT_LE(batches[0].size(), std::size_t(max_evals));
    EXPECT_GE(total, direct.rows.size());
    if (max_evals == 12) {
      // The start and the first round's values around it in one batch, at most 12 of them.
      EXPECT_EQ(batches[0].size(), 12u);
      EXPECT_LT(batches.size(), direct.rows.size());  // fewer arrays than points
    }
  }
}

TEST(TuneCandidates, RoundTripAndRefuseOtherOptions) {
  const fs::path dir = test::fresh_temp_dir("tune_candidates");
  TunePoint start;
  start.detect.hypotheses = 3;
  std::vector<TunePoint> points{start, start};
  points[1].detect.ref_ratio = 0.02;
  points[1].angle_steps = 45;
  const fs::path file = write_candidates(dir, points);
  EXPECT_EQ(write_candidates(dir, points), file);  // named by its content
  const std::vector<TunePoint> back = read_candidates(file, start);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_TRUE(same_point(back[0], points[0]));
  EXPECT_TRUE(same_point(back[1], points[1]));

  TunePoint other = start;
  other.detect.hypotheses = 5;  // a task started with other options than the file's
  EXPECT_THROW(read_candidates(file, other), InputError);
  EXPECT_THROW(read_candidates(dir / "missing.json", start), InputError);
  for (const char* text : {"", "{\"points\": []}", "{\"points\": [{\"ref-ratio\": 0.1}]}", "[1]"}) {
    const fs::path bad = dir / "bad.json";
    std::ofstream(bad) << text;
    EXPECT_THROW(read_candidates(bad, start), InputError) << text;
  }
}
