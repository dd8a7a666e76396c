// BOP's visibility rule (bop_toolkit calc_gt_info.py, visib_mode bop19, delta 15 mm) on a
// hand-made image: a part partly behind another surface within and beyond 15 mm, and where the
// depth image has no data.
#include <gtest/gtest.h>

#include "host/core/error.hpp"
#include "synth/bop_visibility.hpp"

using namespace binpick;

namespace {

// 12 x 3 pixels, fx = fy = 10, principal point (1, 1): pixel (11, 1) looks 45 degrees off axis.
Eigen::Matrix3d K() {
  Eigen::Matrix3d k;
  k << 10, 0, 1, 0, 10, 1, 0, 0, 1;
  return k;
}
constexpr std::uint32_t kW = 12, kH = 3;
std::uint32_t at(std::uint32_t u, std::uint32_t v) { return v * kW + u; }

}  // namespace

TEST(BopVisibility, FollowsTheToolkitsRule) {
  // Depth image in 0.1 mm units; the part lies at z = 1000 mm on six pixels.
  std::vector<std::uint16_t> raw(kW * kH, 20000);
  PartSilhouette part;
  const auto add = [&](std::uint32_t u, std::uint32_t v, std::uint16_t scene) {
    part.pixels.push_back(at(u, v));
    part.depth_mm.push_back(1000.0f);
    raw[at(u, v)] = scene;
  };
  add(1, 0, 10000);  // the part itself: visible
  add(2, 0, 9900);   // 10 mm in front of it: within delta, visible
  add(3, 0, 9800);   // 20 mm in front: hidden
  add(4, 1, 0);      // no depth: visible (bop19), not valid
  add(5, 2, 12000);  // the surface is behind the part (noise): visible
  add(11, 1, 9880);  // 12 mm in depth but 12 * sqrt(2) = 17 mm in distance: hidden
  const BopVisibility v = bop_visibility(part, {kW, kH, &raw, 0.1}, K(), kBopVisibDelta, true);
  EXPECT_EQ(v.px_count_valid, 5u);
  EXPECT_EQ(v.px_count_visib, 4u);
  EXPECT_EQ(v.visible, (std::vector<std::uint32_t>{at(1, 0), at(2, 0), at(4, 1), at(5, 2)}));
  EXPECT_EQ(v.bbox_visib, (std::array<int, 4>{1, 0, 4, 2}));  // [x, y, max x - x, max y - y]
}

TEST(BopVisibility, ExactlyDeltaIsVisible) {
  std::vector<std::uint16_t> raw(kW * kH, 0);
  raw[at(1, 1)] = 985;  // 15 mm in front of the part, on the axis (distance = depth)
  const PartSilhouette part{{at(1, 1)}, {1000.0f}};
  EXPECT_EQ(bop_visibility(part, {kW, kH, &raw, 1.0}, K()).px_count_visib, 1u);
  raw[at(1, 1)] = 984;
  const BopVisibility hidden = bop_visibility(part, {kW, kH, &raw, 1.0}, K());
  EXPECT_EQ(hidden.px_count_visib, 0u);
  EXPECT_EQ(hidden.px_count_valid, 1u);
  EXPECT_EQ(hidden.bbox_visib, (std::array<int, 4>{-1, -1, -1, -1}));
}

TEST(BopVisibility, BadInputIsAnInputError) {
  std::vector<std::uint16_t> raw(kW * kH, 0), small(5, 0);
  EXPECT_THROW(bop_visibility({{kW * kH}, {1.0f}}, {kW, kH, &raw, 1.0}, K()), InputError);
  EXPECT_THROW(bop_visibility({{0, 1}, {1.0f}}, {kW, kH, &raw, 1.0}, K()), InputError);
  EXPECT_THROW(bop_visibility({{0}, {1.0f}}, {kW, kH, &small, 1.0}, K()), InputError);
}
