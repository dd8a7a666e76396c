// Distractor lists and the mix of kinds in a bin (synth/part_mix.hpp): parsing MODEL[:FRACTION],
// the shares of --objects, and the seeded shuffle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "host/core/error.hpp"
#include "synth/part_mix.hpp"

using namespace binpick;

TEST(PartMix, ParsesModelsAndFractions) {
  const auto specs = parse_distractors("builtin:bolt,builtin:tee:0.2,parts/a:b.stl,x.ply:0.05");
  ASSERT_EQ(specs.size(), 4u);
  EXPECT_EQ(specs[0].model, "builtin:bolt");  // "bolt" is no number: part of the name
  EXPECT_FALSE(specs[0].fraction);
  EXPECT_EQ(specs[1].model, "builtin:tee");
  EXPECT_DOUBLE_EQ(*specs[1].fraction, 0.2);
  EXPECT_EQ(specs[2].model, "parts/a:b.stl");
  EXPECT_FALSE(specs[2].fraction);
  EXPECT_EQ(specs[3].model, "x.ply");
  EXPECT_DOUBLE_EQ(*specs[3].fraction, 0.05);
  // Without fractions, 0.25 split evenly over all the distractors listed.
  const auto f = distractor_fractions(specs);
  EXPECT_DOUBLE_EQ(f[0], 0.0625);
  EXPECT_DOUBLE_EQ(f[1], 0.2);
}

TEST(PartMix, RejectsMalformedListsAndFractions) {
  for (const char* bad :
       {"", ",", "builtin:bolt,", ",builtin:bolt", "builtin:bolt,,x.ply", "builtin:bolt:0",
        "builtin:bolt:1", "builtin:bolt:-0.1", "builtin:bolt:nan", "builtin:bolt:inf", ":0.5"})
    EXPECT_THROW(parse_distractors(bad), InputError) << bad;
}

TEST(PartMix, CountsShareTheObjects) {
  EXPECT_EQ(kind_counts(16, parse_distractors("a.ply:0.25,b.ply")), (std::vector<int>{10, 4, 2}));
  EXPECT_EQ(kind_counts(350, {}), (std::vector<int>{350}));
  EXPECT_THROW(kind_counts(10, parse_distractors("a.ply:0.6,b.ply:0.5")), InputError);  // sum >= 1
  EXPECT_THROW(kind_counts(1, parse_distractors("a.ply:0.6")), InputError);  // none left for obj 1
}

TEST(PartMix, SequenceIsASeededShuffle) {
  const std::vector<int> counts{10, 4, 2};
  const auto a = mixed_sequence(counts, 7), b = mixed_sequence(counts, 7),
             c = mixed_sequence(counts, 8);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  ASSERT_EQ(a.size(), 16u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(std::count(a.begin(), a.end(), k), counts[std::size_t(k)]);
  // Mixed: the distractors are not all at the end.
  EXPECT_NE(a, (std::vector<int>{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2}));
  // One kind: no shuffle, the drop of a single part.
  EXPECT_EQ(mixed_sequence({5}, 7), (std::vector<int>(5, 0)));
}
