// `binpick synth` is deterministic end to end, as a user runs it: the same --seed into two
// directories gives byte-identical scene_gt.json, another seed another one. (The drop alone is
// tested in test_drop.cpp; this covers the seeds per bin, the decomposition cache and the
// writer too.)
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <fmt/format.h>

#include "tests/support/cli_run.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;

TEST(SynthDeterminism, SameSeedSameGroundTruthOtherSeedOther) {
  const fs::path dir = test::fresh_temp_dir("synth_determinism");
  struct RemoveAtEnd {  // also when an assertion ends the test early
    fs::path dir;
    ~RemoveAtEnd() { fs::remove_all(dir); }
  } remove_at_end{dir};
  // The first run fills the decomposition cache and the second reads it: both paths must
  // give the same hulls. One small wave and a tiny image keep it to seconds.
  const auto synth = [&](const std::string& out, int seed) {
    const auto run = test::run_binpick(fmt::format(
        "synth --model builtin:bracket --out '{}' --bins 2 --objects 12 --seed {} "
        "--width 64 --height 36 --no-cloud --cache-dir '{}'",
        (dir / out).string(), seed, (dir / "cache").string()));
    EXPECT_EQ(run.status, 0) << run.err;
  };
  synth("a", 5);
  synth("b", 5);
  synth("c", 6);
  const auto gt = [&](const std::string& out, const std::string& bin) {
    return test::slurp(dir / out / "test" / bin / "scene_gt.json");
  };
  for (const std::string bin : {"000000", "000001"}) {
    const std::string a = gt("a", bin);
    ASSERT_FALSE(a.empty()) << "no scene_gt.json in bin " << bin;
    EXPECT_EQ(a, gt("b", bin)) << "bin " << bin;
    EXPECT_NE(a, gt("c", bin)) << "bin " << bin;
  }
  // The two bins of one run are drawn from different seeds, too.
  EXPECT_NE(gt("a", "000000"), gt("a", "000001"));
}

// Bins drop side by side on threads (drops_ahead.hpp): one thread or three, the same files, the
// depth images as the ground truth; a rerun that extends the dataset drops only the new bins.
TEST(SynthDeterminism, ThreadsDoNotChangeTheDataset) {
  const fs::path dir = test::fresh_temp_dir("synth_threads");
  struct RemoveAtEnd {
    fs::path dir;
    ~RemoveAtEnd() { fs::remove_all(dir); }
  } remove_at_end{dir};
  const auto synth = [&](const std::string& out, int bins, int threads) {
    const auto run = test::run_binpick(fmt::format(
        "synth --model builtin:bracket --out '{}' --bins {} --objects 12 --seed 9 "
        "--width 64 --height 36 --no-cloud --threads {} --cache-dir '{}'",
        (dir / out).string(), bins, threads, (dir / "cache").string()));
    EXPECT_EQ(run.status, 0) << run.err;
  };
  synth("one", 3, 1);
  synth("three", 3, 3);
  synth("extended", 1, 2);
  synth("extended", 3, 2);
  for (const std::string bin : {"000000", "000001", "000002"})
    for (const std::string file : {"scene_gt.json", "depth/000000.png"}) {
      const std::string one = test::slurp(dir / "one" / "test" / bin / file);
      ASSERT_FALSE(one.empty()) << bin << "/" << file;
      EXPECT_EQ(one, test::slurp(dir / "three" / "test" / bin / file)) << bin << "/" << file;
      EXPECT_EQ(one, test::slurp(dir / "extended" / "test" / bin / file)) << bin << "/" << file;
    }
  const auto refused = test::run_binpick(fmt::format(
      "synth --model builtin:bracket --out '{}' --bins 1 --threads -1", (dir / "bad").string()));
  EXPECT_NE(refused.status, 0);
  EXPECT_NE(refused.err.find("--threads"), std::string::npos) << refused.err;
}

}  // namespace
}  // namespace binpick
