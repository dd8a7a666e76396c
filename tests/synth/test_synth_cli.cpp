// `binpick synth` as a user runs it: --help, bad options refused before anything is written,
// and a dataset that resumes, extends, replaces a bin left half-written, and refuses to mix in
// bins made with other settings or by another version of the generator; a model file gets the
// symmetries found on its mesh.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "tests/support/cli_run.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& name) : path(test::fresh_temp_dir(name)) {}
  ~TempDir() { fs::remove_all(path); }
};

// One small wave and a tiny image: seconds a bin.
std::string synth_args(const fs::path& out, const fs::path& cache, const std::string& extra) {
  return fmt::format(
      "synth --model builtin:bracket --out '{}' --objects 8 --width 64 --height 36 --no-cloud "
      "--cache-dir '{}' {}",
      out.string(), cache.string(), extra);
}

TEST(SynthCli, HelpNamesTheOptions) {
  const auto r = test::run_binpick("synth --help");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* option : {"--model", "--out", "--bins", "--objects", "--seed", "--noise",
                             "--bin-size", "--grid", "--final-settle", "--max-wall-seconds",
                             "--bin-render", "--bin-wall", "--bin-rim", "--bin-mesh",
                             "--distractors", "--intrinsics", "--camera-tilt"})
    EXPECT_NE(r.out.find(option), std::string::npos) << option;
}

TEST(SynthCli, BadOptionsFailWithOneMessageAndWriteNothing) {
  const TempDir dir("synth_bad");
  const fs::path out = dir.path / "data";
  for (const std::string extra : {"--bins 0", "--objects 0", "--noise -1", "--noise nan",
                                  "--width 5", "--bin-size 1,2", "--seed x", "--drop-height -5",
                                  "--camera-height 10", "--grid 0,5",
                                  // the bin, the distractors and the camera
                                  "--bin-render half", "--bin-wall 0", "--bin-rim -1",
                                  "--bin-wall nan", "--bin-mesh /nonexistent/bin.ply",
                                  "--distractors ,builtin:bolt", "--distractors builtin:bolt,",
                                  "--distractors builtin:bolt:1.5", "--distractors builtin:bolt:0",
                                  "--distractors builtin:bolt:nan",
                                  "--distractors builtin:bolt:0.6,builtin:tee:0.5",
                                  "--distractors builtin:nosuch", "--camera-tilt nan",
                                  "--camera-tilt 95", "--intrinsics 1,2,3",
                                  "--intrinsics -5,5,1,1", "--intrinsics 5,5,nan,1"}) {
    const auto r = test::run_binpick(synth_args(out, dir.path / "cache", extra));
    EXPECT_EQ(r.status, 2) << extra;  // CLI11's parse errors too (--seed x, --bin-size 1,2)
    EXPECT_FALSE(r.err.empty()) << extra;
    EXPECT_LE(std::count(r.err.begin(), r.err.end(), '\n'), 2) << extra << ": " << r.err;
    EXPECT_FALSE(fs::exists(out / "test" / "000000")) << extra;
  }
  const auto missing = test::run_binpick(
      fmt::format("synth --model '{}' --out '{}'", (dir.path / "nope.ply").string(), out.string()));
  EXPECT_EQ(missing.status, 2);
  EXPECT_NE(missing.err.find("nope.ply"), std::string::npos) << missing.err;
}

TEST(SynthCli, ResumesExtendsAndRefusesOtherSettings) {
  const TempDir dir("synth_resume");
  const fs::path out = dir.path / "data", cache = dir.path / "cache";
  auto r = test::run_binpick(synth_args(out, cache, "--bins 1"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("1 bins made, 0 already there"), std::string::npos) << r.out;
  const std::string first = test::slurp(out / "test" / "000000" / "scene_gt.json");

  // An interrupted run leaves its bin in a hidden staging directory; the next run replaces it.
  fs::create_directories(out / "test" / ".000001.partial");
  std::ofstream(out / "test" / ".000001.partial" / "scene_gt.json") << "{ half";
  r = test::run_binpick(synth_args(out, cache, "--bins 2"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("1 bins made, 1 already there"), std::string::npos) << r.out;
  EXPECT_EQ(test::slurp(out / "test" / "000000" / "scene_gt.json"), first);  // kept as it was
  EXPECT_TRUE(fs::exists(out / "test" / "000001" / "scene_gt.json"));
  EXPECT_FALSE(fs::exists(out / "test" / ".000001.partial"));
  EXPECT_NO_THROW(nlohmann::json::parse(test::slurp(out / "test" / "000001" / "scene_gt.json")));

  // Other settings would mix two kinds of bins in one dataset.
  r = test::run_binpick(synth_args(out, cache, "--bins 3 --seed 2"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("seed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("another --out"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out / "test" / "000002"));

  // So would bins made by an older generator (its synth.json has no or another version).
  auto manifest = nlohmann::json::parse(test::slurp(out / "synth.json"));
  ASSERT_TRUE(manifest.contains("synth_version"));
  manifest.erase("synth_version");
  std::ofstream(out / "synth.json") << manifest.dump(1);
  r = test::run_binpick(synth_args(out, cache, "--bins 3"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("synth_version"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out / "test" / "000002"));
}

TEST(SynthCli, AModelFileGetsTheSymmetriesFoundOnIt) {
  // The bolt's stated symmetries, then the same mesh as a model file (the dataset's own copy):
  // models_info.json gets the symmetries found on it, the same six-fold turns.
  const TempDir dir("synth_symmetry");
  const fs::path stated = dir.path / "stated", found = dir.path / "found";
  const fs::path cache = dir.path / "cache";
  auto args = [&](const std::string& model, const fs::path& out) {
    return fmt::format(
        "synth --model '{}' --out '{}' --objects 2 --grid 2,1 --width 32 --height 32 --no-cloud "
        "--cache-dir '{}'",
        model, out.string(), cache.string());
  };
  auto r = test::run_binpick(args("builtin:bolt", stated));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(
      r.out.find("symmetry (stated for the built-in part): 5 discrete: 6-fold about (0, 0, 1)"),
      std::string::npos)
      << r.out;
  r = test::run_binpick(args((stated / "models" / "obj_000001.ply").string(), found));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("symmetry (found on the mesh): 5 discrete: 6-fold about (0, 0, 1)"),
            std::string::npos)
      << r.out;
  auto info = [](const fs::path& out) {
    return nlohmann::json::parse(test::slurp(out / "models" / "models_info.json"))["1"];
  };
  const auto want = info(stated)["symmetries_discrete"], got = info(found)["symmetries_discrete"];
  ASSERT_EQ(got.size(), want.size());
  ASSERT_EQ(got.size(), 5u);
  // Compared as sets: each stated transform has a found one within 1e-3 in every entry.
  for (const auto& w : want) {
    bool matched = false;
    for (const auto& g : got) {
      bool close = true;
      for (std::size_t k = 0; k < 16; ++k) close &= std::fabs(double(g[k]) - double(w[k])) < 1e-3;
      matched |= close;
    }
    EXPECT_TRUE(matched) << w.dump();
  }
}

}  // namespace
}  // namespace binpick
