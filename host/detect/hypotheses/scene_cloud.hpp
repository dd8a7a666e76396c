// Scene preparation and highest points for an unstructured cloud (`detect --cloud`, for data
// with no depth image), camera frame, mm. Host implementations for now (clouds are the rare
// input; the depth-image path is the device pipeline): "highest" is the smallest z, the
// low-pass is the mean z of the points within a lateral (x, y) radius -- the equivalent of the
// range image's window, found with a uniform grid -- and normals, when the cloud has none, come
// from a PCA of the points within a 3D radius, oriented towards the camera.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "host/detect/hypotheses/hypotheses.hpp"
#include "host/detect/scene/scene_crop.hpp"
#include "host/core/mesh.hpp"

namespace binpick {

struct CloudHypothesisOptions {
  HypothesisOptions hypotheses;
  float lowpass_radius = 3.0f;  // mm, lateral radius of the mean z
  // mm; neighbours whose z differs more from the point's are left out of its mean. A cloud is
  // densest in (x, y) on steep surfaces, so without this gate the floor beside a part borrows
  // the part's height and outranks lower part tops. Infinity gives the plain mean.
  float lowpass_max_jump = 10.0f;
};

// Throws InputError for a NaN or infinite coordinate or normal, or normals of another size.
void check_cloud(const PointCloud& cloud);

// Per point, the mean z of the points whose (x, y) lie within radius and whose z lies within
// max_jump of the point's (itself included).
std::vector<float> cloud_lowpass_z(const PointCloud& cloud, float radius,
                                   float max_jump = INFINITY);

// Per point, the unit normal of the least-squares plane through the points within radius
// (3D), oriented so n . p < 0; zero where fewer than 3 points or a degenerate fit.
std::vector<Eigen::Vector3f> cloud_normals(const PointCloud& cloud, float radius);

// The highest points of a cloud: Hypothesis::pixel is the point index, u = v = 0, depth the
// filtered z, point = (x, y, filtered z). Same rounds and tie-break as for an image.
std::vector<Hypothesis> find_hypotheses(const PointCloud& cloud,
                                        const CloudHypothesisOptions& opt = {});

// The points (and normals, if any) of a cloud inside a sphere, in cloud order. With
// require_normals, points whose normal is zero are dropped (a cloud without normals is an error).
PointCloud crop_sphere(const PointCloud& cloud, const CropOptions& opt);

}  // namespace binpick
