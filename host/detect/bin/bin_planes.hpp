// Dominant planes of a scene for the bin fit (bin_fit.hpp): sequential RANSAC over a sparse
// sample of the point image. Candidate planes come from point triples drawn near each other in
// the image (a thin rim or a partly hidden floor still yields whole triples), all candidates of a
// round are scored at once on the device (kernels/bin_planes.cl: inlier counts), the best is
// refitted to its inliers by least squares, and its inliers leave the sample for the next round.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "host/runtime/cl/cl_buffer.hpp"
#include "kernels/scene_mask_shared.h"

namespace binpick {

// A rectangle of pixels, [u0, u1) x [v0, v1); u1 = 0: the whole image.
struct PixelWindow {
  std::uint32_t u0 = 0, v0 = 0, u1 = 0, v1 = 0;
};

// A sparse sample of a point image: every stride-th pixel in both directions that has data.
struct PlaneSamples {
  std::vector<Eigen::Vector3f> points;             // mm, camera frame
  std::vector<std::uint32_t> u, v;                 // their pixels
  std::uint32_t stride = 1, width = 0, height = 0; // of the image sampled
  // The window whose border the rim is looked for along (bin_rim.hpp's border band): the
  // whole image, or what stands above the ground all around a bin (bin_ground.hpp).
  PixelWindow window;
};

// The grid stride that samples at most about max_points of `valid` points with data.
std::uint32_t sample_stride(std::size_t valid, std::size_t max_points);

// Samples at most about max_points of the points with data (xyzw a pixel, w = 0 without).
PlaneSamples sample_points(const std::vector<float>& xyzw, std::uint32_t width,
                           std::uint32_t height, std::size_t max_points = 40000);
// The same samples from the point image on the device (float4 a pixel), of which `valid` pixels
// have data: only the grid is read back (kernel bin_sample_grid), not the whole image.
PlaneSamples sample_points(ocl::Device& dev, const ocl::Buffer<float>& points,
                           std::uint32_t width, std::uint32_t height, std::size_t valid,
                           std::size_t max_points = 40000);

// Routine: inlier counts (|n . p + d| <= tol) of every plane over the points, on the device.
std::vector<std::uint32_t> count_plane_inliers(ocl::Device& dev,
                                               const std::vector<Eigen::Vector3f>& points,
                                               const std::vector<bp_plane>& planes, float tol);
// Reference: the same float predicate (bp_plane_distance) in plain C++; equal counts.
std::vector<std::uint32_t> count_plane_inliers_reference(const std::vector<Eigen::Vector3f>& points,
                                                         const std::vector<bp_plane>& planes,
                                                         float tol);

struct FoundPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, facing the camera (n . p < 0)
  double d = 0;                                       // n . p + d = 0
  std::vector<std::uint32_t> inliers;                 // sample indices within tol
};

struct PlaneSearch {
  std::size_t max_planes = 5;
  std::size_t candidates = 256;   // triples scored per round
  double min_fraction = 0.02;     // a plane needs this fraction of the samples (and 50 points)
  float tol = 5.0f;               // inlier distance, mm
  std::uint32_t seed = 1;         // deterministic: same samples, same planes
};

// Sequential RANSAC; planes in the order found (most supported first).
std::vector<FoundPlane> find_planes(ocl::Device& dev, const PlaneSamples& samples,
                                    const PlaneSearch& opt);

}  // namespace binpick
