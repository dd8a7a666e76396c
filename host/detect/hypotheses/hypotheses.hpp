// The highest-point heuristic (paper section III-C): the `count` highest points (nearest the
// camera) of the low-pass filtered range image, each excluding its neighbourhood (radius
// slightly larger than the part diameter) from the next (kernels/hypotheses.cl).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "host/runtime/cl/cl_buffer.hpp"
#include "host/detect/scene/scene_prepare.hpp"
#include "host/core/timing.hpp"
#include "host/detect/scene/depth_to_points.hpp"

namespace binpick {

struct HypothesisOptions {
  std::uint32_t count = 5;        // the paper's 5
  float exclusion_radius = 60.0f;  // mm; slightly larger than the diameter (52 in the paper)
  // Highest along this unit direction (the bin's up, from its floor towards the camera's side)
  // instead of nearest the camera: a pixel's key is -up . p, p its point at the filtered depth.
  // For a camera looking straight down (up = -z) that is the depth itself, the paper's rule; for
  // a tilted camera the nearest points lie on the bin's near side, not on top of the pile.
  // None: nearest the camera.
  std::optional<Eigen::Vector3f> up = std::nullopt;
};

struct Hypothesis {
  std::uint32_t pixel = 0;  // row-major pixel index (point index for a cloud)
  std::uint32_t u = 0, v = 0;  // pixel column and row (0 for a cloud)
  float depth = 0.0f;          // filtered depth (mm)
  Eigen::Vector3f point = Eigen::Vector3f::Zero();  // on the pixel's ray at that depth (mm)
};

void check(const HypothesisOptions& opt);

// The tiles of the rounds with a camera (find_hypotheses; kernel hyp_tile_argmin): tile (tx, ty) holds columns
// [tx w, tx w + w) and rows [ty h, ty h + h), cut at the image's edge; its result is entry
// ty x + tx.
struct Tiles {
  std::uint32_t w = 32, h = 32;  // pixels
  std::uint32_t x = 0, y = 0;    // tiles across and down
  std::size_t count() const { return std::size_t(x) * y; }
};
Tiles tiles_for(std::uint32_t width, std::uint32_t height);

// Routine: on the device, from a point image and its filtered depth (one float a pixel,
// 0 = no data). Highest first (nearest the camera, or along opt.up); fewer than count when the
// valid pixels run out. With a mask (one byte a pixel, scene_mask.hpp), pixels it does not
// keep start excluded: they never become a highest point (the exclusion around each chosen
// point is unchanged).
// camera: the camera whose depth_to_points made the points (of the same width x height), if
// they were made so: then a round excludes only in the rectangle the exclusion sphere projects
// into (crop_pixel_rect) and looks again only at the tiles (Tiles) it touches: the same
// hypotheses for less work. Without one every round scans the whole image (any point image).
std::vector<Hypothesis> find_hypotheses(ocl::Device& dev, const PointImage& points,
                                        const std::vector<float>& filtered,
                                        const HypothesisOptions& opt = {},
                                        const std::vector<std::uint8_t>* mask = nullptr,
                                        const bp_camera* camera = nullptr);
// Reference: the same rounds in plain C++ (same float predicate: the same pixels exactly).
std::vector<Hypothesis> find_hypotheses_reference(const PointImage& points,
                                                  const std::vector<float>& filtered,
                                                  const HypothesisOptions& opt = {},
                                                  const std::vector<std::uint8_t>* mask = nullptr);

// Reference of the keys the rounds compare when opt.up is given (kernel hyp_height_key): -up . p
// of each pixel's point at its filtered depth, 0 where there is none, the least positive float
// where -up . p <= 0.
std::vector<float> height_keys_reference(const PointImage& points,
                                         const std::vector<float>& filtered,
                                         const Eigen::Vector3f& up);

// The rounds on device buffers (one read-back at the end; with a camera one small read-back a
// round, for the rectangle); mask and camera as above (mask n bytes) or null.
std::vector<Hypothesis> find_hypotheses(ocl::Device& dev, const ocl::Buffer<float>& points,
                                        const ocl::Buffer<float>& filtered, std::uint32_t width,
                                        std::uint32_t height, const HypothesisOptions& opt,
                                        const ocl::Buffer<std::uint8_t>* mask = nullptr,
                                        const bp_camera* camera = nullptr);

// On a prepared scene: the kernels on its device buffers if it has them, else the C++ reference
// on its host images (a scene from prepare_scene_reference). Appends the stage "hypotheses" to
// timings if given.
std::vector<Hypothesis> find_hypotheses(const PreparedScene& scene,
                                        const HypothesisOptions& opt = {},
                                        StageTimings* timings = nullptr);

}  // namespace binpick
