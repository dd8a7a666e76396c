// Inputs and checks shared by the highest-point kernel tests (tests/detect/hypotheses/test_kernels_hypotheses.cpp,
// test_hypothesis_tiles.cpp): filtered depths with ties, random exclusion flags, and a selected
// hypothesis against its reference (pixel, u, v, depth and z exactly, x and y within 4 ulp: a
// float division and a product; OpenCL allows its division 2.5 ulp).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "host/detect/scene/scene_lowpass.hpp"
#include "kernels/binpick_shared.h"
#include "kernels/scene_shared.h"

namespace binpick::test {

// Filtered depths of a point image: the low-pass reference rounded to 1/4 mm, so that many
// pixels share the smallest value (ties).
inline std::vector<float> tied_filtered(const PointImage& pts, int radius) {
  std::vector<float> f = lowpass_depth_reference(pts, radius);
  for (float& x : f) x = std::round(x * 4.0f) / 4.0f;
  return f;
}

inline std::vector<std::uint8_t> random_flags(std::mt19937& rng, std::size_t n, double p) {
  std::bernoulli_distribution b(p);
  std::vector<std::uint8_t> out(n);
  for (auto& x : out) x = b(rng) ? 1 : 0;
  return out;
}

inline void expect_near_ulps(float got, float want, int ulps, const std::string& what) {
  EXPECT_LE(std::fabs(got - want), ulps * std::numeric_limits<float>::epsilon() * std::fabs(want))
      << what << ": " << got << " vs " << want;
}

inline void expect_same(const bp_hypothesis& got, const bp_hypothesis& want, const std::string& at) {
  EXPECT_EQ(got.pixel, want.pixel) << at;
  EXPECT_EQ(got.u, want.u) << at;
  EXPECT_EQ(got.v, want.v) << at;
  EXPECT_EQ(got.depth, want.depth) << at;
  EXPECT_EQ(got.z, want.z) << at;
  expect_near_ulps(got.x, want.x, 4, at + " x");
  expect_near_ulps(got.y, want.y, 4, at + " y");
  EXPECT_EQ(got.reserved[0], 0u) << at;
  EXPECT_EQ(got.reserved[1], 0u) << at;
}

}  // namespace binpick::test
