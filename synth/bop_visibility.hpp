// BOP's visibility of a ground-truth part (bop_toolkit's calc_gt_info.py with
// visibility.estimate_visib_mask_gt, visib_mode "bop19", delta 15 mm), from the part drawn alone
// and the depth image as written: a pixel of the part's unoccluded silhouette is visible where
// the model's distance along the ray is at most delta behind the depth image's, or where the
// depth image has no data; px_count_valid counts the silhouette's pixels with data, occlusion
// ignored. Distances, not depths: the toolkit turns both images into distances from the camera
// centre (depth * |((u - cx) / fx, (v - cy) / fy, 1)|) before comparing.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "synth/render/part_silhouette.hpp"

namespace binpick {

// BOP's tolerance of the visibility test (calc_gt_info.py's delta), mm.
inline constexpr double kBopVisibDelta = 15.0;

struct BopVisibility {
  std::uint32_t px_count_valid = 0, px_count_visib = 0;
  std::array<int, 4> bbox_visib{-1, -1, -1, -1};  // [x, y, w, h], w = max x - min x
  std::vector<std::uint32_t> visible;             // the visible pixels (BOP's mask_visib), if asked
};

// The depth image as the toolkit reads it: raw PNG values (0 = no data) times depth_scale (mm).
struct BopDepthImage {
  std::uint32_t width = 0, height = 0;
  const std::vector<std::uint16_t>* raw = nullptr;
  double depth_scale = 1.0;
};

// InputError for a silhouette whose pixels and depths differ in number or leave the image, or
// a depth image of the wrong size.
// keep_pixels: also list the visible pixels, in silhouette order.
BopVisibility bop_visibility(const PartSilhouette& part, const BopDepthImage& depth,
                             const Eigen::Matrix3d& K, double delta = kBopVisibDelta,
                             bool keep_pixels = false);

}  // namespace binpick
