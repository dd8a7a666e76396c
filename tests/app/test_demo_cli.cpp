// `binpick demo` as a user runs it (smaller than its defaults, to keep the test short): it exits
// 0, prints the devices, the table (bins, precision at both operating points, ms per hypothesis)
// and where the report and pictures are; the same command again reuses everything. A part that
// is not built in exits 2 with one message.
#include <gtest/gtest.h>

#include <algorithm>

#include <fmt/format.h>

#include "tests/support/cli_run.hpp"

using namespace binpick;
namespace fs = std::filesystem;

TEST(DemoCli, PrintsTheTableAndWhereTheReportIsAndResumes) {
  const fs::path dir = test::fresh_temp_dir("demo_cli");
  const fs::path out = dir / "demo";
  const std::string cmd =
      fmt::format("demo --out {} --bins 1 --objects 20", out.string());
  auto r = test::run_binpick(cmd);
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  for (const char* text : {"OpenCL: ", "Vulkan: ", "loose 10%/15deg", "strict 5%/5deg", "ms/hyp",
                           "bins", "report:", "pictures:"})
    EXPECT_NE(r.out.find(text), std::string::npos) << text << "\n" << r.out;
  EXPECT_NE(r.out.find((out / "report" / "report.html").string()), std::string::npos) << r.out;
  EXPECT_GT(fs::file_size(out / "report" / "report.html"), 0u);
  EXPECT_FALSE(fs::is_empty(out / "report" / "pictures"));

  r = test::run_binpick(cmd);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("reused"), std::string::npos) << r.out;
  fs::remove_all(dir);
}

TEST(DemoCli, UnknownPartExits2WithOneMessage) {
  const fs::path dir = test::fresh_temp_dir("demo_bad");
  const auto r = test::run_binpick(fmt::format("demo --out {} --part nosuch", (dir / "d").string()));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("nosuch"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir / "d"));
  fs::remove_all(dir);
}
