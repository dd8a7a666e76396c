// `binpick parts` as a user runs it: output on stdout, exit status, one message on stderr for
// bad input, and no output left behind by a failed run.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "host/core/diameter.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "synth/parts/builtin_parts.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;

struct RunResult {
  int status = -1;
  std::string out;
  std::string err;
};

class CliParts : public testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() / ("binpick_cli_parts_" + std::to_string(::getpid()) + "_" +
                                     testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::string slurp(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

  RunResult run(const std::string& arguments) {
    const fs::path out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    const std::string command = std::string("'") + BINPICK_EXE + "' " + arguments + " >'" +
                                out.string() + "' 2>'" + err.string() + "'";
    const int raw = std::system(command.c_str());
    RunResult result{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(out), slurp(err)};
    fs::remove(out);
    fs::remove(err);
    return result;
  }

  // A failed run: non-zero status, nothing on stdout, exactly one line on stderr containing
  // fragment.
  void expect_failure(const std::string& arguments, const std::string& fragment) {
    SCOPED_TRACE(arguments);
    const RunResult r = run(arguments);
    EXPECT_NE(r.status, 0);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
  }

  fs::path dir_;
};

TEST_F(CliParts, ListPrintsNameTabDescription) {
  const RunResult r = run("parts --list");
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream lines(r.out);
  std::vector<std::string> names;
  for (std::string line; std::getline(lines, line);) {
    const auto tab = line.find('\t');
    ASSERT_NE(tab, std::string::npos) << line;
    EXPECT_GT(line.size(), tab + 1) << "a description follows the tab";
    names.push_back(line.substr(0, tab));
  }
  EXPECT_EQ(names, builtin_part_names());
}

TEST_F(CliParts, OutWritesEveryPartAsGltfByDefault) {
  const RunResult r = run("parts --out '" + (dir_ / "parts").string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const auto& name : builtin_part_names()) {
    const fs::path path = dir_ / "parts" / (name + ".gltf");
    EXPECT_NE(r.out.find(path.string()), std::string::npos) << r.out;
    EXPECT_NEAR(exact_diameter(load_model(path.string(), {}).positions),
                builtin_part_nominal_diameter(name), 1e-4);
  }
}

TEST_F(CliParts, OutWithFormatAndModel) {
  const RunResult stl = run("parts --out '" + dir_.string() + "' --format stl");
  ASSERT_EQ(stl.status, 0) << stl.err;
  EXPECT_TRUE(fs::exists(dir_ / "bolt.stl"));
  // Convert one model: STL in metres to a PLY in mm.
  const RunResult ply =
      run("parts --out '" + (dir_ / "converted").string() + "' --format ply --model '" +
          (dir_ / "bolt.stl").string() + "' --unit-scale 1000");
  ASSERT_EQ(ply.status, 0) << ply.err;
  EXPECT_NEAR(exact_diameter(load_model((dir_ / "converted" / "bolt.ply").string(), {}).positions),
              52000, 0.1);
}

TEST_F(CliParts, InfoDescribesTheModel) {
  const RunResult r = run("parts --info --model builtin:tee --diameter 100");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("diameter (mm): 100"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("closed and consistently oriented: yes"), std::string::npos) << r.out;
}

TEST_F(CliParts, BadInputFailsWithOneMessageAndNoOutput) {
  const std::string out = " --out '" + (dir_ / "never").string() + "'";
  expect_failure("parts --info --model '" + (dir_ / "missing.ply").string() + "'", "missing.ply");
  expect_failure("parts --info --model builtin:sprocket", "bracket");
  expect_failure("parts --info --model builtin:bolt --unit-scale -2", "unit scale");
  expect_failure("parts --info --model builtin:bolt --diameter 0", "diameter");
  expect_failure("parts --info", "--model");
  expect_failure("parts", "nothing to do");
  expect_failure("parts" + out + " --format xyz", "xyz");
  std::ofstream(dir_ / "broken.ply") << "ply\nformat ascii 1.0\nelement vertex 3\n";
  expect_failure("parts" + out + " --model '" + (dir_ / "broken.ply").string() + "'", "broken.ply");
  EXPECT_FALSE(fs::exists(dir_ / "never")) << "a failed run leaves no output behind";
}

}  // namespace
}  // namespace binpick
