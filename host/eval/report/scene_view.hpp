// One image of a dataset as the report's pictures need it: depth, intensity, the camera-frame
// point of every pixel, and projection back into the image.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "host/formats/bop/png_image.hpp"
#include "host/eval/metrics/eval_dataset.hpp"

namespace binpick::eval {

struct SceneView {
  GrayImage<std::uint16_t> depth_raw;
  GrayImage<std::uint8_t> gray;       // empty (0 x 0) if the dataset has none
  double depth_scale = 1.0;           // mm per depth unit
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  std::vector<Eigen::Vector3f> points;  // per pixel, camera frame, mm; z = 0 where no data

  double depth_mm(std::size_t pixel) const { return depth_raw.pixels[pixel] * depth_scale; }
  // Pixel coordinates (column, row) of a camera-frame point; nullopt behind the camera.
  std::optional<Eigen::Vector2d> project(const Eigen::Vector3d& p) const;
};

// Reads test/NNNNNN/depth/III.png (required) and gray/III.png (optional) of image key.
SceneView load_scene_view(const Dataset& dataset, const ImageKey& key);

}  // namespace binpick::eval
