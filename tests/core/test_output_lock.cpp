// OutputLock: one holder per output at a time, released when its holder ends in any way
// (SIGKILL included), with a message that names the output and the holder's pid.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "host/core/error.hpp"
#include "host/core/output_lock.hpp"
#include "tests/support/cli_run.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;

// The message of the InputError `lock` throws, or "" if it took the lock.
template <class Lock>
std::string refusal(const Lock& lock) {
  try {
    lock();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Shards of one batch write one output at once: each holds it shared and its own shard lock
// exclusively. Two shards coexist; the same shard twice, or an unsharded run beside a shard (in
// either order), is refused. Files too. A shard leaves other writers' temporaries alone.
TEST(OutputLock, ShardsShareTheOutputButNotTheirShard) {
  const fs::path dir = test::fresh_temp_dir("lock_shards") / "out";
  {
    const OutputLock one = OutputLock::directory(dir, 0, 3);
    const OutputLock two = OutputLock::directory(dir, 1, 3);
    EXPECT_NE(refusal([&] { OutputLock::directory(dir, 1, 3); })
                  .find("shard 2/3 of " + dir.string() + " is in use by another binpick"),
              std::string::npos);
    EXPECT_NE(refusal([&] { OutputLock::directory(dir); }).find("is in use by another binpick"),
              std::string::npos);
  }
  {
    const OutputLock whole = OutputLock::directory(dir);
    EXPECT_NE(refusal([&] { OutputLock::directory(dir, 2, 3); }).find("is in use"),
              std::string::npos);
  }
  const fs::path file = dir / "results.csv";
  {
    const OutputLock one = OutputLock::file(file, 0, 2);
    EXPECT_EQ(refusal([&] { OutputLock::file(file, 1, 2); }), "");
    EXPECT_NE(refusal([&] { OutputLock::file(file); }).find("is in use"), std::string::npos);
    EXPECT_NE(refusal([&] { OutputLock::file(file, 0, 2); }).find("shard 1/2 of"),
              std::string::npos);
  }
  // A running shard's temporary survives another shard's lock.
  const fs::path temporary = dir / ".scene_000001.json.tmp12345_0";
  std::ofstream(temporary) << "half";
  { const OutputLock shard = OutputLock::directory(dir, 1, 2); }
  EXPECT_TRUE(fs::exists(temporary));
}

TEST(OutputLock, SecondHolderOfADirectoryIsRefusedWithThePid) {
  const fs::path dir = test::fresh_temp_dir("lock_dir") / "out";
  {
    const OutputLock first = OutputLock::directory(dir);  // creates the directory
    EXPECT_TRUE(fs::is_directory(dir));
    EXPECT_EQ(first.lock_path(), dir / ".binpick.lock");
    const std::string message = refusal([&] { OutputLock::directory(dir); });
    EXPECT_NE(message.find(dir.string() + " is in use by another binpick (pid " +
                           std::to_string(::getpid()) + ")"),
              std::string::npos)
        << message;
  }
  EXPECT_EQ(refusal([&] { OutputLock::directory(dir); }), "") << "released by the destructor";
  fs::remove_all(dir.parent_path());
}

TEST(OutputLock, FilesAreLockedBesideThemAndIndependently) {
  const fs::path dir = test::fresh_temp_dir("lock_file");
  const OutputLock a = OutputLock::file(dir / "a.csv");
  EXPECT_EQ(a.lock_path(), dir / ".a.csv.lock");
  EXPECT_FALSE(fs::exists(dir / "a.csv")) << "the output itself is not touched";
  EXPECT_EQ(refusal([&] { OutputLock::file(dir / "b.csv"); }), "");
  EXPECT_NE(refusal([&] { OutputLock::file(dir / "a.csv"); }).find("in use"), std::string::npos);
  OutputLock moved = OutputLock::file(dir / "c.csv");
  const OutputLock kept(std::move(moved));
  EXPECT_NE(refusal([&] { OutputLock::file(dir / "c.csv"); }).find("in use"), std::string::npos)
      << "a moved lock is still held";
  fs::remove_all(dir);
}

TEST(OutputLock, AKilledHolderLeavesNoStaleLock) {
  const fs::path dir = test::fresh_temp_dir("lock_kill");
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const OutputLock held = OutputLock::directory(dir);
    [[maybe_unused]] const ssize_t n = ::write(ready[1], "x", 1);
    ::pause();  // until killed
    ::_exit(0);
  }
  char byte = 0;
  ASSERT_EQ(::read(ready[0], &byte, 1), 1);
  const std::string message = refusal([&] { OutputLock::directory(dir); });
  EXPECT_NE(message.find("(pid " + std::to_string(child) + ")"), std::string::npos) << message;
  ::kill(child, SIGKILL);
  ::waitpid(child, nullptr, 0);
  EXPECT_EQ(refusal([&] { OutputLock::directory(dir); }), "");
  ::close(ready[0]);
  ::close(ready[1]);
  fs::remove_all(dir);
}

// What a writer killed mid-write leaves (write_file_atomically's and the plots' temporaries)
// is removed once the lock is held, and nothing else.
TEST(OutputLock, TakingTheLockRemovesKilledWritersTemporaries) {
  const fs::path dir = test::fresh_temp_dir("lock_sweep");
  fs::create_directories(dir / "out" / "report");
  fs::create_directories(dir / "out" / "test" / ".000001.partial");
  fs::create_directories(dir / "r.csv.parts");
  for (const fs::path& p :
       {dir / "out" / "report" / ".precision.png.4711.partial", dir / "out" / ".synth.json.tmp12_0",
        dir / "out" / "keep.csv", dir / "out" / ".tmp12_0", dir / ".r.csv.tmp5_1",
        dir / ".r.details.csv.tmp5_2", dir / ".other.csv.tmp5_3",
        dir / "r.csv.parts" / ".scene_000000.csv.tmp9_9"})
    std::ofstream(p) << "x";
  {
    const OutputLock out = OutputLock::directory(dir / "out");
    EXPECT_FALSE(fs::exists(dir / "out" / "report" / ".precision.png.4711.partial"));
    EXPECT_FALSE(fs::exists(dir / "out" / ".synth.json.tmp12_0"));
    EXPECT_TRUE(fs::exists(dir / "out" / "keep.csv"));
    EXPECT_TRUE(fs::exists(dir / "out" / ".tmp12_0")) << "not a name a writer gives";
    EXPECT_TRUE(fs::is_directory(dir / "out" / "test" / ".000001.partial")) << "synth's own";
  }
  const OutputLock results = OutputLock::file(dir / "r.csv");
  EXPECT_FALSE(fs::exists(dir / ".r.csv.tmp5_1"));
  EXPECT_FALSE(fs::exists(dir / ".r.details.csv.tmp5_2"));
  EXPECT_FALSE(fs::exists(dir / "r.csv.parts" / ".scene_000000.csv.tmp9_9"));
  EXPECT_TRUE(fs::exists(dir / ".other.csv.tmp5_3")) << "another output's";
  fs::remove_all(dir);
}

TEST(OutputLock, AnOutputThatIsAFileIsNotADirectory) {
  const fs::path dir = test::fresh_temp_dir("lock_notdir");
  { std::ofstream(dir / "plain") << "x"; }
  EXPECT_NE(refusal([&] { OutputLock::directory(dir / "plain"); }).find("not a directory"),
            std::string::npos);
  EXPECT_NE(refusal([&] { OutputLock::file(dir / "missing" / "r.csv"); }).find("cannot create"),
            std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace binpick
