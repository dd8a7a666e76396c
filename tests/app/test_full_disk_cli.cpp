// A full disk and a read-only output (issue 17): one clear message, no partial file (no
// truncated PNG, JSON or PLY, no temporary file, no half-written bin), and a later run with
// space completes. The disk is a small tmpfs mounted for the test: skipped where mount(2) is
// not permitted (not root, or no CAP_SYS_ADMIN in a container).
#include <gtest/gtest.h>

#include <stdlib.h>
#include <sys/mount.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

#include <fmt/format.h>

#include "tests/support/cli_run.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;

// A tmpfs of `size` at a fresh directory, unmounted (lazily) at the end.
class SmallDisk {
 public:
  SmallDisk(const std::string& name, const std::string& size)
      : parent_(test::fresh_temp_dir(name)), dir_(parent_ / "disk") {
    fs::create_directories(dir_);
    if (::mount("tmpfs", dir_.c_str(), "tmpfs", 0, ("size=" + size).c_str()) == 0)
      mounted_ = true;
    else
      error_ = std::strerror(errno);
  }
  ~SmallDisk() {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
    fs::remove_all(parent_);
  }
  bool mounted() const { return mounted_; }
  const std::string& error() const { return error_; }
  const fs::path& dir() const { return dir_; }
  const fs::path& parent() const { return parent_; }
  // Remounts with other options ("size=64m", "ro"); false if refused.
  bool remount(unsigned long flags, const std::string& options) {
    return ::mount("tmpfs", dir_.c_str(), "tmpfs", MS_REMOUNT | flags, options.c_str()) == 0;
  }

 private:
  fs::path parent_, dir_;
  bool mounted_ = false;
  std::string error_;
};

// Names of the files and directories under `dir` that an interrupted or failed write leaves:
// temporary files (.NAME.tmpPID_N) and staging directories (.NNNNNN.partial).
std::vector<std::string> leftovers(const fs::path& dir) {
  std::vector<std::string> found;
  if (!fs::exists(dir)) return found;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.find(".tmp") != std::string::npos || name.ends_with(".partial"))
      found.push_back(entry.path().string());
  }
  return found;
}

// BINPICK_QUIET=1 (set by the tests): no progress lines, so stderr is the error alone.
void expect_one_error_line(const test::CliRun& r, const std::string& wanted) {
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err.rfind("binpick: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(wanted), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

std::string synth_args(const fs::path& out, const fs::path& cache) {
  // 640 x 480 with the scene cloud: several MB a bin, more than the 2 MB disk holds.
  return fmt::format("synth --model builtin:bolt --objects 6 --bins 2 --width 640 --height 480 "
                     "--cache-dir '{}' --out '{}'",
                     cache.string(), out.string());
}

TEST(FullDiskCli, SynthOnAFullDiskSaysSoLeavesNoPartialFileAndResumesWithSpace) {
  ::setenv("BINPICK_QUIET", "1", 1);
  SmallDisk disk("full_disk", "2m");
  if (!disk.mounted()) GTEST_SKIP() << "mount -t tmpfs not permitted here: " << disk.error();
  const fs::path out = disk.dir() / "data", cache = disk.parent() / "cache";
  const auto full = test::run_binpick(synth_args(out, cache));
  expect_one_error_line(full, "No space left on device");
  EXPECT_EQ(leftovers(out), std::vector<std::string>{});
  EXPECT_FALSE(fs::exists(out / "test" / "000000")) << "no bin is there unless it is whole";

  ASSERT_TRUE(disk.remount(0, "size=64m"));
  const auto resumed = test::run_binpick(synth_args(out, cache));
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  for (const char* bin : {"000000", "000001"})
    EXPECT_TRUE(fs::exists(out / "test" / bin / "scene_gt.json")) << bin;
  EXPECT_EQ(leftovers(out), std::vector<std::string>{});
}

TEST(FullDiskCli, AReadOnlyOutputIsOneMessageAndNothingWritten) {
  ::setenv("BINPICK_QUIET", "1", 1);
  SmallDisk disk("read_only", "4m");
  if (!disk.mounted()) GTEST_SKIP() << "mount -t tmpfs not permitted here: " << disk.error();
  fs::create_directories(disk.dir() / "existing");
  ASSERT_TRUE(disk.remount(MS_RDONLY, ""));
  const fs::path cache = disk.parent() / "cache";
  expect_one_error_line(test::run_binpick(synth_args(disk.dir() / "new", cache)),
                        "Read-only file system");
  expect_one_error_line(test::run_binpick(synth_args(disk.dir() / "existing", cache)),
                        "Read-only file system");
  expect_one_error_line(
      test::run_binpick(fmt::format("detect --model nothing.ppfm --dataset nothing --out '{}'",
                                    (disk.dir() / "existing" / "results.csv").string())),
      "Read-only file system");
  EXPECT_TRUE(fs::is_empty(disk.dir() / "existing"));
  EXPECT_FALSE(fs::exists(disk.dir() / "new"));
}

}  // namespace
}  // namespace binpick
