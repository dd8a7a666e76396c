// Two binpicks on one output: every verb that writes an output directory or file refuses to
// start while another holds it (here: this test, through the same lock), with one message that
// names the output and the holder's pid, exit 2, and without touching the output.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include <fmt/format.h>

#include "host/core/output_lock.hpp"
#include "tests/support/cli_run.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;

void expect_refused(const std::string& args, const fs::path& out) {
  const auto r = test::run_binpick(args);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
  EXPECT_NE(r.err.find("binpick: error: " + out.string() + " is in use by another binpick (pid " +
                       std::to_string(::getpid()) + ")"),
            std::string::npos)
      << args << "\n" << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST(OutputLockCli, DirectoryVerbsRefuseAnOutputInUse) {
  const fs::path dir = test::fresh_temp_dir("lock_cli_dir");
  const fs::path out = dir / "out";
  {
    const OutputLock held = OutputLock::directory(out);
    expect_refused(fmt::format("synth --model builtin:bolt --objects 4 --bins 1 --width 32 "
                               "--height 32 --out '{}'", out.string()),
                   out);
    expect_refused(fmt::format("run --model builtin:bolt --objects 4 --bins 1 --width 32 "
                               "--height 32 --out '{}'", out.string()),
                   out);
    EXPECT_FALSE(fs::exists(out / "test")) << "the refused synth wrote nothing";
    EXPECT_FALSE(fs::exists(out / "noise_0.00")) << "the refused run wrote nothing";
  }
  // Released: the same command runs.
  const auto r = test::run_binpick(fmt::format(
      "synth --model builtin:bolt --objects 4 --bins 1 --width 32 --height 32 --no-cloud "
      "--cache-dir '{}' --out '{}'", (dir / "cache").string(), out.string()));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "test" / "000000" / "scene_gt.json"));
  fs::remove_all(dir);
}

TEST(OutputLockCli, FileVerbsRefuseAnOutputInUse) {
  const fs::path dir = test::fresh_temp_dir("lock_cli_file");
  const fs::path results = dir / "results.csv", model = dir / "part.ppfm";
  const OutputLock held_results = OutputLock::file(results);
  const OutputLock held_model = OutputLock::file(model);
  expect_refused(fmt::format("detect --model '{}' --dataset '{}' --out '{}'", model.string(),
                             dir.string(), results.string()),
                 results);
  expect_refused(fmt::format("train --model builtin:bolt --out '{}'", model.string()), model);
  EXPECT_FALSE(fs::exists(results));
  EXPECT_FALSE(fs::exists(model));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace binpick
