// Runs the built `binpick` executable from a test, as a user would, and captures what it says.
#pragma once

#include <filesystem>
#include <string>

namespace binpick::test {

struct CliRun {
  int status = -1;  // exit status, -1 if it did not exit normally (a crash)
  std::string out, err;
};

// `binpick ARGS` (ARGS as a shell would split them). Safe to call from tests running in
// parallel: each call captures into its own temporary files.
CliRun run_binpick(const std::string& args);

// An empty directory of its own for this process and test, under the system's temp directory;
// removed when the test process exits (kept if BINPICK_KEEP_TEST_DIRS is set).
std::filesystem::path fresh_temp_dir(const std::string& name);

std::string slurp(const std::filesystem::path& path);

// A results CSV without its last column, `time` (the only part that may change between runs).
std::string without_time(const std::string& csv);

}  // namespace binpick::test
