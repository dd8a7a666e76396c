#include "tests/support/cli_run.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <sstream>
#include <vector>

namespace binpick::test {

namespace fs = std::filesystem;

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string without_time(const std::string& csv) {
  std::string out;
  std::size_t start = 0;
  while (start < csv.size()) {
    std::size_t end = csv.find('\n', start);
    if (end == std::string::npos) end = csv.size();
    const std::string line = csv.substr(start, end - start);
    out += line.substr(0, line.rfind(',')) + "\n";
    start = end + 1;
  }
  return out;
}

namespace {

// The test process's temporary directories, removed when it exits (unless
// BINPICK_KEEP_TEST_DIRS is set, to look at a failing test's files): a suite run must not leave
// hundreds of datasets in /tmp.
class TempDirs {
 public:
  void add(const fs::path& dir) {
    const std::lock_guard<std::mutex> lock(mutex_);
    dirs_.push_back(dir);
  }
  ~TempDirs() {
    if (std::getenv("BINPICK_KEEP_TEST_DIRS") != nullptr) return;
    for (const auto& dir : dirs_) {
      std::error_code ignored;  // a destructor never throws
      fs::remove_all(dir, ignored);
    }
  }

 private:
  std::mutex mutex_;
  std::vector<fs::path> dirs_;
};

TempDirs& temp_dirs() {
  static TempDirs dirs;
  return dirs;
}

}  // namespace

fs::path fresh_temp_dir(const std::string& name) {
  static std::atomic<int> counter{0};
  const fs::path dir = fs::temp_directory_path() / ("binpick_test_" + name + "_" +
                                                    std::to_string(::getpid()) + "_" +
                                                    std::to_string(counter++));
  fs::remove_all(dir);
  fs::create_directories(dir);
  temp_dirs().add(dir);
  return dir;
}

CliRun run_binpick(const std::string& args) {
  const fs::path dir = fresh_temp_dir("cli");
  const fs::path out = dir / "stdout", err = dir / "stderr";
  const std::string command = std::string("'") + BINPICK_EXE + "' " + args + " >'" +
                              out.string() + "' 2>'" + err.string() + "' </dev/null";
  const int raw = std::system(command.c_str());
  CliRun r{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(out), slurp(err)};
  fs::remove_all(dir);
  return r;
}

}  // namespace binpick::test
