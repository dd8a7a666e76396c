// The low-pass filtered range image of the highest-point heuristic (paper section III-C):
// a box mean of the valid depths around each valid pixel (kernels/scene_lowpass.cl).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "host/runtime/cl/cl_buffer.hpp"
#include "host/detect/scene/depth_to_points.hpp"

namespace binpick {

// Routine: per pixel the mean z (mm) of the valid pixels in the (2r+1)^2 window, r in [0, 64];
// 0 where the pixel itself has no data (holes are not filled). With a mask (one byte a pixel,
// scene_mask.hpp) only the pixels it keeps count as valid: the low-pass of the masked points.
std::vector<float> lowpass_depth(ocl::Device& dev, const PointImage& points, int radius,
                                 const std::vector<std::uint8_t>* mask = nullptr);
// Reference: the same separable sums in the same order, in plain C++.
std::vector<float> lowpass_depth_reference(const PointImage& points, int radius,
                                           const std::vector<std::uint8_t>* mask = nullptr);

// The passes on device buffers (points float4 a pixel, filtered one float a pixel, mask one
// byte a pixel or null), enqueued without waiting; their scratch is allocated here. The mask is
// read in place: the masked points are never written out.
void enqueue_lowpass_depth(ocl::Device& dev, const ocl::Buffer<float>& points,
                           std::uint32_t width, std::uint32_t height, int radius,
                           ocl::Buffer<float>& filtered,
                           const ocl::Buffer<std::uint8_t>* mask = nullptr);

void check_lowpass_radius(int radius);

// Routine: the points (float4 a pixel, n pixels) moved along their rays to the low-passed depth
// where it has a value (filtered > 0; elsewhere the point as it is): the depth image with the
// sensor's noise averaged over the low-pass box, which the in-plane search of thin parts reads
// when the noise is deeper than half the sheet's thickness (plane_search.hpp). Enqueued without
// waiting.
void enqueue_lowpass_points(ocl::Device& dev, const ocl::Buffer<float>& points,
                            const ocl::Buffer<float>& filtered, std::size_t n,
                            ocl::Buffer<float>& out);
// Reference: the same float operations in plain C++ (xyzw: 4 floats a pixel).
std::vector<float> lowpass_points_reference(const std::vector<float>& xyzw,
                                            const std::vector<float>& filtered);

// The row and column passes (lowpass_rows, lowpass_cols) take a block of this many pixels of
// one row a work item (LP_BLOCK in kernels/scene_lowpass.cl): their global size.
inline constexpr std::uint32_t kLowpassBlock = 8;
std::size_t lowpass_work_items(std::uint32_t width, std::uint32_t height);

}  // namespace binpick
