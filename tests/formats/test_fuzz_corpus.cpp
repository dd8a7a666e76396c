// Replays the fuzzers' stored inputs in the normal build: every file of fuzz/corpus/NAME (seeds)
// and fuzz/regressions/NAME (inputs that once crashed a parser) through target NAME's body
// (fuzz/targets.cpp). Each must parse or be rejected with InputError; any other exception fails
// the test, and a crash ends it. The seeds are valid files: each target has some, and all parse.
#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz/targets.hpp"
#include "host/core/error.hpp"

using namespace binpick;
namespace fs = std::filesystem;

namespace {

const fs::path fuzz_dir = fs::path(BINPICK_SOURCE_DIR) / "fuzz";

// The mesh loader's warnings about the repairs it makes are expected here.
const bool quiet_loader = [] {
  spdlog::set_level(spdlog::level::err);
  return true;
}();

std::string bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

// The files of dir, sorted (none if it does not exist).
std::vector<fs::path> files_in(const fs::path& dir) {
  std::vector<fs::path> files;
  if (fs::is_directory(dir))
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

struct Replay {
  std::size_t parsed = 0, rejected = 0;
};

// Runs every file of dir through target; a failure names the file and the exception.
Replay replay(const fuzz::Target& target, const fs::path& dir) {
  Replay r;
  for (const auto& file : files_in(dir)) {
    const std::string bytes = bytes_of(file);
    try {
      target.parse(bytes);
      ++r.parsed;
    } catch (const InputError&) {
      ++r.rejected;
    } catch (const std::exception& e) {
      ADD_FAILURE() << file << ": " << target.name << " threw a non-InputError exception: "
                    << e.what();
    } catch (...) {
      ADD_FAILURE() << file << ": " << target.name << " threw something that is not an exception";
    }
  }
  return r;
}

std::set<std::string> target_names() {
  std::set<std::string> names;
  for (const auto& t : fuzz::all_targets()) names.insert(t.name);
  return names;
}

}  // namespace

TEST(FuzzCorpus, EveryTargetHasSeedsAndTheyParse) {
  for (const auto& target : fuzz::all_targets()) {
    const fs::path dir = fuzz_dir / "corpus" / target.name;
    SCOPED_TRACE(dir.string());
    ASSERT_FALSE(files_in(dir).empty()) << "no seed inputs for fuzz target " << target.name;
    // The seeds are valid files: one that no longer parses means a parser stopped reading
    // what it should (and the fuzzer would start from less).
    for (const auto& file : files_in(dir)) {
      try {
        target.parse(bytes_of(file));
      } catch (const std::exception& e) {
        ADD_FAILURE() << file << " does not parse: " << e.what();
      }
    }
  }
}

TEST(FuzzCorpus, RegressionsParseOrAreRejectedCleanly) {
  std::size_t total = 0;
  for (const auto& target : fuzz::all_targets()) {
    const fs::path dir = fuzz_dir / "regressions" / target.name;
    SCOPED_TRACE(dir.string());
    const Replay r = replay(target, dir);
    total += r.parsed + r.rejected;
  }
  RecordProperty("regression_inputs", static_cast<int>(total));
}

// A folder under fuzz/corpus or fuzz/regressions that names no target would never be replayed.
TEST(FuzzCorpus, EveryFolderNamesATarget) {
  const auto names = target_names();
  for (const char* kind : {"corpus", "regressions"}) {
    const fs::path root = fuzz_dir / kind;
    if (!fs::is_directory(root)) continue;
    for (const auto& entry : fs::directory_iterator(root)) {
      if (!entry.is_directory()) continue;
      EXPECT_TRUE(names.count(entry.path().filename().string()))
          << entry.path() << " is not the name of a fuzz target (fuzz/targets.cpp)";
    }
  }
}

// The target list and the fuzzer executables agree: fuzz/fuzz_NAME.cpp for every target.
TEST(FuzzCorpus, EveryTargetHasAFuzzer) {
  for (const auto& name : target_names())
    EXPECT_TRUE(fs::is_regular_file(fuzz_dir / ("fuzz_" + name + ".cpp"))) << name;
}
