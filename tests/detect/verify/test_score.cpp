// The verified score as one model (host/detect/verify/score.hpp): the factor table, each pure
// factor function on hand-computed cases, and how the breakdown combines (multiply in order,
// zero, cap, then the look-alike share).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

#include "host/detect/verify/score.hpp"

namespace binpick {
namespace {

TEST(ScoreFactors, TheTableHasOneUniquelyNamedRowPerFactorInOrder) {
  const auto table = score_factors();
  ASSERT_EQ(table.size(), std::size_t(kScoreFactorCount));
  std::set<std::string> names;
  for (const ScoreFactorInfo& f : table) {
    EXPECT_TRUE(names.insert(f.name).second) << f.name;
    EXPECT_FALSE(std::string(f.meaning).empty()) << f.name;
  }
  EXPECT_STREQ(table[kAgreement].name, "agreement");
  EXPECT_STREQ(table[kBelowFloor].name, "below_floor");
  EXPECT_EQ(table[kBelowFloor].combine, FactorCombine::zero);
  EXPECT_EQ(table[kRivalCap].combine, FactorCombine::cap);
  EXPECT_STREQ(table[kLookalikeShare].name, "lookalike_share");
  // The factors that need other poses come after the ones of a pose alone, but for the ray
  // spread, whose noise floor is the image's (phase 1).
  for (std::size_t f = kRivalCap; f < kScoreFactorCount; ++f)
    EXPECT_EQ(table[f].scope, FactorScope::poses) << table[f].name;
}

TEST(ScoreFactors, Agreement) {
  // support = 100 - 20 / 2 = 90, above the minimum support of 30.
  EXPECT_DOUBLE_EQ(agreement_factor(45.0, 100, 20, 30.0), 0.5);
  // A sliver: 10 visible points, support 10, divided by the minimum support instead.
  EXPECT_DOUBLE_EQ(agreement_factor(9.0, 10, 0, 30.0), 0.3);
  EXPECT_DOUBLE_EQ(score_support(10, 0, 0.0), 10.0);
  EXPECT_DOUBLE_EQ(score_support(1, 1, 0.0), 1.0);  // never below one point
  EXPECT_EQ(agreement_factor(5.0, 0, 0, 1.0), 0.0);   // nothing visible
  EXPECT_EQ(agreement_factor(5.0, 7, 7, 1.0), 0.0);   // no depth where it is visible
}

TEST(ScoreFactors, SeeThroughOutlineAndShare) {
  EXPECT_EQ(see_through_factor(0.0, 50, 100.0), 1.0);  // off
  EXPECT_DOUBLE_EQ(see_through_factor(1.0, 25, 100.0), 0.75);
  EXPECT_DOUBLE_EQ(see_through_factor(2.0, 25, 100.0), 0.5);
  EXPECT_EQ(see_through_factor(10.0, 25, 100.0), 0.0);  // never negative
  EXPECT_EQ(outline_factor(0, 0), 1.0);                 // no outline cells: no evidence
  EXPECT_DOUBLE_EQ(outline_factor(3, 1), 0.75);
  EXPECT_EQ(outline_factor(0, 5), 0.0);
  EXPECT_DOUBLE_EQ(lookalike_share_factor(0.8, 0.8, 1.0), 0.5);  // a tie halves
  EXPECT_DOUBLE_EQ(lookalike_share_factor(0.6, 0.2, 1.0), 0.75);
  EXPECT_DOUBLE_EQ(lookalike_share_factor(0.6, 0.2, 0.5), 0.6 / 0.7);
  EXPECT_EQ(lookalike_share_factor(0.6, 0.0, 1.0), 1.0);  // no look-alike scores
  EXPECT_EQ(lookalike_share_factor(0.0, 0.9, 1.0), 1.0);  // zero stays zero (not NaN)
}

TEST(ScoreBreakdown, CombinesInPhasesAndOrder) {
  ScoreBreakdown b;
  EXPECT_EQ(b.score(), 0.0);  // unverified: agreement 0
  b[kAgreement] = 0.9;
  EXPECT_DOUBLE_EQ(b.score(), 0.9);  // every other factor starts neutral
  b[kPatchBias] = 0.5;
  b[kRaySpread] = 0.8;
  b[kEdgeStep] = 0.5;
  const double product = ((0.9 * 0.5) * 0.8) * 0.5;
  EXPECT_EQ(b.per_pose(), product);  // bit for bit: the same multiplications in the same order
  EXPECT_EQ(b.fit(), product);
  // A cap above the product does nothing; below it, the cap is the fit; below zero, zero.
  b[kRivalCap] = 0.5;
  EXPECT_EQ(b.fit(), product);
  b[kRivalCap] = 0.1;
  EXPECT_EQ(b.fit(), 0.1);
  b[kRivalCap] = -0.2;
  EXPECT_EQ(b.fit(), 0.0);
  b[kRivalCap] = 0.1;
  // The share multiplies the fit.
  b[kLookalikeShare] = 0.5;
  EXPECT_DOUBLE_EQ(b.score(), 0.05);
  EXPECT_DOUBLE_EQ(b.fit(), 0.1);
  // Below the floor: zero whatever else.
  b[kBelowFloor] = 0;
  EXPECT_EQ(b.per_pose(), 0.0);
  EXPECT_EQ(b.score(), 0.0);
}

TEST(ScoreBreakdown, DescribesAndWritesItsFactors) {
  ScoreBreakdown b;
  b[kAgreement] = 0.912;
  EXPECT_EQ(describe_factors(b), "agreement 0.912");
  b[kPatchBias] = 0.75;
  b[kRivalCap] = 0.31;
  EXPECT_EQ(describe_factors(b), "agreement 0.912 x patch_bias 0.750 x rival_cap 0.310");
  const std::string cells = factor_columns(b);
  EXPECT_EQ(cells, ",0.912000,1.000000,1.000000,0.750000,1.000000,1.000000,1.000000,1.000000,"
                   "1.000000,0.310000,1.000000");
  b[kRivalCap] = INFINITY;  // no cap: an empty cell
  EXPECT_TRUE(factor_columns(b).ends_with(",1.000000,,1.000000")) << factor_columns(b);
}

}  // namespace
}  // namespace binpick

namespace binpick {
namespace {

// docs/detect/verify.md holds the score's table between two markers; when it differs from the
// code's, the code's is written to the build directory, to copy in.
TEST(ScoreFactors, TheDocsTableIsTheTable) {
  const std::filesystem::path docs =
      std::filesystem::path(BINPICK_SOURCE_DIR) / "docs" / "detect" / "verify.md";
  std::ifstream in(docs);
  ASSERT_TRUE(in) << docs;
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string begin = "<!-- score-table: begin -->\n", end = "<!-- score-table: end -->";
  const auto a = text.find(begin), b = text.find(end);
  ASSERT_NE(a, std::string::npos) << docs << " has no " << begin;
  ASSERT_NE(b, std::string::npos) << docs << " has no " << end;
  if (text.substr(a + begin.size(), b - a - begin.size()) != score_table_markdown()) {
    const auto wanted = std::filesystem::current_path() / "score_table.md";
    std::ofstream(wanted) << score_table_markdown();
    FAIL() << docs << "'s score table differs from the code's: the code's is in " << wanted
           << "; copy it between the markers";
  }
}

}  // namespace
}  // namespace binpick
