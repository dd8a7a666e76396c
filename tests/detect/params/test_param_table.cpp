// The one parameter table (host/detect/params/param_table.hpp): every parameter once, each range
// enforced at its edges, the --params file written and read back from it (on/off as true/false
// or 1/0, older names still read), the command line's options made from it, and the table in
// docs/parameters.md equal to it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/core/error.hpp"
#include "host/core/read_file.hpp"
#include "host/detect/params/param_table.hpp"
#include "host/detect/params/params_file.hpp"
#include "tests/support/cli_run.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;

TEST(ParamTable, EveryParameterOnceWithADefaultInItsRange) {
  std::set<std::string> names;
  for (const ParamInfo& p : detect_param_table()) {
    EXPECT_TRUE(names.insert(p.name).second) << p.name;
    EXPECT_FALSE(std::string(p.help).empty()) << p.name;
    EXPECT_EQ(find_param(p.name), &p);
    if (p.old_name) {
      EXPECT_EQ(find_param(p.old_name), &p);
    }
  }
  // Every member of DetectParams is a row: the file written from the table holds them all, and
  // one member per row (two rows on one member would collide here).
  const auto json = nlohmann::json::parse(params_json(DetectParams{}));
  EXPECT_EQ(json.size(), names.size());
  EXPECT_NO_THROW(check(DetectParams{}));
  EXPECT_EQ(find_param("no-such-parameter"), nullptr);
}

TEST(ParamTable, EachRangeHoldsAtItsEdgesAndNoFurther) {
  for (const ParamInfo& p : detect_param_table()) {
    if (is_flag(p) || is_text(p)) continue;
    SCOPED_TRACE(p.name);
    const auto set = [&](DetectParams& params, double v) {
      std::visit(
          [&](auto member) {
            using T = std::remove_cvref_t<decltype(params.*member)>;
            if constexpr (std::is_same_v<T, double>) params.*member = v;
            else if constexpr (std::is_same_v<T, std::uint32_t>) params.*member = std::uint32_t(v);
          },
          p.member);
    };
    const auto problem = [&](double v) {
      DetectParams params;
      set(params, v);
      const auto bad = find_param_problem(params);
      return bad ? bad->name : std::string();
    };
    const ParamRange& r = p.range;
    EXPECT_EQ(problem(r.hi), "");
    const double step = is_count(p) ? 1.0 : 1e-6 * std::max(1.0, r.hi);
    EXPECT_EQ(problem(r.hi + step), p.name);
    if (r.lo_open) {
      EXPECT_EQ(problem(r.lo), p.name);
      EXPECT_EQ(problem(r.lo + step), "");
    } else {
      EXPECT_EQ(problem(r.lo), "");
      if (r.lo - step >= 0 || !is_count(p)) {
        EXPECT_EQ(problem(r.lo - step), p.name);
      }
    }
    if (r.or_zero) {
      EXPECT_EQ(problem(0), "");
    }
    if (!is_count(p)) {
      EXPECT_EQ(problem(NAN), p.name);
      EXPECT_EQ(problem(INFINITY), p.name);
    }
  }
}

TEST(ParamsFile, RoundTripsFlagsTakeOneOrZeroAndOlderNamesAreRead) {
  DetectParams p;
  p.hypotheses = 9;
  p.over_rim = true;
  p.local_peaks = false;
  p.verify_rival = 3.5;
  p.bin = "600,400,300";
  DetectParams back;
  apply_params_text(params_json(p), "p.json", back);
  EXPECT_EQ(params_json(back), params_json(p));
  EXPECT_TRUE(back.over_rim);
  EXPECT_FALSE(back.local_peaks);

  DetectParams old;
  apply_params_text(R"({"over_rim": 1, "local-peaks": 0, "verify_twin": 0.02})", "old.json", old);
  EXPECT_TRUE(old.over_rim);
  EXPECT_FALSE(old.local_peaks);
  EXPECT_EQ(old.verify_lookalike_holes, 0.02);
  // The command line's given parameters are kept, by their names now.
  DetectParams kept;
  apply_params_text(R"({"verify_twin": 0.02})", "old.json", kept, {"verify-lookalike-holes"});
  EXPECT_EQ(kept.verify_lookalike_holes, DetectParams{}.verify_lookalike_holes);

  for (const char* bad : {R"({"over-rim": 2})", R"({"over-rim": "on"})", R"({"hypotheses": -1})",
                          R"({"hypotheses": 1.5})", R"({"ref-ratio": "x"})", R"({"bin": 3})",
                          R"([1, 2])", R"({"nope": 1})", "{"}) {
    DetectParams q;
    EXPECT_THROW(apply_params_text(bad, "bad.json", q), InputError) << bad;
  }
}

TEST(ParamTable, TheCommandLineHasAnOptionPerRow) {
  const auto r = test::run_binpick("detect --help");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const ParamInfo& p : detect_param_table()) {
    EXPECT_NE(r.out.find(fmt::format("--{}", p.name)), std::string::npos) << p.name;
    if (is_flag(p)) {
      EXPECT_NE(r.out.find(fmt::format("--no-{}", p.name)), std::string::npos) << p.name;
    }
  }
  EXPECT_NE(r.out.find("Detection parameters: verification"), std::string::npos) << r.out;
}

// docs/parameters.md holds the table between two markers; when they differ, the table as it
// should be is written to the build directory, to copy in.
TEST(ParamTable, TheDocsTableIsTheTable) {
  const fs::path docs = fs::path(BINPICK_SOURCE_DIR) / "docs" / "parameters.md";
  const std::string text = read_file_bytes(docs);
  const std::string begin = "<!-- param-table: begin -->\n", end = "<!-- param-table: end -->";
  const auto a = text.find(begin), b = text.find(end);
  ASSERT_NE(a, std::string::npos) << docs << " has no " << begin;
  ASSERT_NE(b, std::string::npos) << docs << " has no " << end;
  const std::string in_docs = text.substr(a + begin.size(), b - a - begin.size());
  const std::string expected = param_table_markdown();
  if (in_docs != expected) {
    const fs::path wanted = fs::current_path() / "param_table.md";
    std::ofstream(wanted) << expected;
    FAIL() << docs << "'s parameter table differs from the code's: the code's is in " << wanted
           << "; copy it between the markers";
  }
}

}  // namespace
}  // namespace binpick
