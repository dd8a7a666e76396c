// The flood that crosses holes (gap_flood.hpp) against an exhaustive search on random images: with
// joins that do not depend on the path, the pixels it enters in either order (breadth first, or
// fewest missing pixels first) are exactly those some chain of steps reaches, each missing run at
// most max_gap long.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include "host/detect/bin/gap_flood.hpp"

namespace binpick {
namespace {

// Every state (pixel, missing pixels crossed since the last with data) reachable from the seeds,
// none pruned: the pixels with data among them.
std::set<std::size_t> exhaustive_flood(std::uint32_t w, std::uint32_t h,
                                       const std::vector<std::size_t>& seeds,
                                       const std::vector<std::uint8_t>& missing,
                                       const std::vector<std::uint8_t>& ok, std::uint32_t max_gap) {
  const std::size_t n = std::size_t(w) * h;
  std::vector<std::uint8_t> seen(n * (max_gap + 1), 0);
  std::vector<std::pair<std::size_t, std::uint32_t>> stack;
  std::set<std::size_t> out;
  for (const std::size_t s : seeds) stack.push_back({s, 0}), seen[s * (max_gap + 1)] = 1;
  while (!stack.empty()) {
    const auto [p, g] = stack.back();
    stack.pop_back();
    if (g == 0) out.insert(p);
    const std::size_t u = p % w, v = p / w;
    std::vector<std::size_t> next;
    if (u > 0) next.push_back(p - 1);
    if (u + 1 < w) next.push_back(p + 1);
    if (v > 0) next.push_back(p - w);
    if (v + 1 < h) next.push_back(p + w);
    for (const std::size_t j : next) {
      std::uint32_t gj = 0;
      if (missing[j]) {
        gj = g + 1;
        if (gj > max_gap) continue;
      } else if (!ok[j]) {
        continue;
      }
      if (!seen[j * (max_gap + 1) + gj]) seen[j * (max_gap + 1) + gj] = 1, stack.push_back({j, gj});
    }
  }
  return out;
}

TEST(GapFlood, EntersWhatAnExhaustiveSearchReachesOnRandomImages) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    SCOPED_TRACE(trial);
    const std::uint32_t w = 5 + rng() % 40, h = 1 + rng() % 30, max_gap = rng() % 6;
    const std::size_t n = std::size_t(w) * h;
    const double missing_share = std::uniform_real_distribution<double>(0, 0.8)(rng);
    std::vector<std::uint8_t> missing(n), ok(n);
    for (std::size_t i = 0; i < n; ++i) {
      missing[i] = std::uniform_real_distribution<double>(0, 1)(rng) < missing_share;
      ok[i] = rng() % 5 != 0;
    }
    std::vector<std::size_t> seeds;
    for (int k = 0, count = 1 + int(rng() % 4); k < count; ++k) {
      const std::size_t s = rng() % n;
      if (!missing[s]) seeds.push_back(s);
    }
    const std::set<std::size_t> want = exhaustive_flood(w, h, seeds, missing, ok, max_gap);
    for (const bool path_independent : {false, true}) {
      SCOPED_TRACE(path_independent ? "fewest missing pixels first" : "breadth first");
      std::vector<std::size_t> calls(n, 0);
      const std::vector<std::size_t> got = flood_with_gaps(
          w, h, seeds,
          [&](std::size_t j) {
            ++calls[j];
            return missing[j] != 0;
          },
          [&](std::size_t, std::size_t j) { return ok[j] != 0; }, max_gap, path_independent);
      const std::set<std::size_t> got_set(got.begin(), got.end());
      EXPECT_EQ(got_set.size(), got.size()) << "a pixel entered twice";
      EXPECT_EQ(got_set, want);
      const std::size_t distinct_seeds = std::set<std::size_t>(seeds.begin(), seeds.end()).size();
      ASSERT_GE(got.size(), distinct_seeds);
      for (std::size_t i = 0; i < distinct_seeds; ++i)
        EXPECT_TRUE(std::count(seeds.begin(), seeds.end(), got[i])) << "seeds first";
      // Each pixel is looked at from at most its 4 neighbours, a missing one once per gap length it
      // is entered with (so at most 4 * (max_gap + 1) looks at any pixel).
      for (std::size_t i = 0; i < n; ++i) EXPECT_LE(calls[i], 4 * (max_gap + 1)) << i;
    }
  }
}

// Degenerate: no seeds, a seed outside the image, max_gap 0 (no hole crossed), one pixel.
TEST(GapFlood, DegenerateInputs) {
  const auto none = [](std::size_t) { return false; };
  const auto all = [](std::size_t, std::size_t) { return true; };
  EXPECT_TRUE(flood_with_gaps(4, 4, {}, none, all, 3).empty());
  EXPECT_TRUE(flood_with_gaps(4, 4, {16, 100}, none, all, 3).empty());
  EXPECT_EQ(flood_with_gaps(1, 1, {0}, none, all, 0), std::vector<std::size_t>{0});
  // A row 0 1 _ 3 with pixel 2 missing: max_gap 0 stops at 1, max_gap 1 crosses to 3.
  const auto hole = [](std::size_t j) { return j == 2; };
  EXPECT_EQ(flood_with_gaps(4, 1, {0}, hole, all, 0), (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(flood_with_gaps(4, 1, {0}, hole, all, 1), (std::vector<std::size_t>{0, 1, 3}));
}

}  // namespace
}  // namespace binpick
