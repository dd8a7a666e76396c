#include "host/train/surface_sampling.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "host/core/error.hpp"

namespace binpick {
namespace {

// Twice the area vector of triangle t, in double.
Eigen::Vector3d area_vector(const Mesh& mesh, std::size_t t) {
  const auto& tri = mesh.triangles[t];
  const Eigen::Vector3d a = mesh.positions[tri[0]].cast<double>();
  const Eigen::Vector3d b = mesh.positions[tri[1]].cast<double>();
  const Eigen::Vector3d c = mesh.positions[tri[2]].cast<double>();
  return (b - a).cross(c - a);
}

void check(const Mesh& mesh) {
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (std::uint32_t v : mesh.triangles[t])
      if (v >= mesh.positions.size())
        throw InputError("surface sampling: triangle " + std::to_string(t) + " refers to vertex " +
                         std::to_string(v) + " of " + std::to_string(mesh.positions.size()));
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    if (!mesh.positions[i].allFinite())
      throw InputError("surface sampling: vertex " + std::to_string(i) + " is not finite");
}

// Uniform in [0, 1) from the top 53 bits: the same numbers on every standard library.
double uniform01(std::mt19937_64& rng) { return double(rng() >> 11) * 0x1.0p-53; }

}  // namespace

double surface_area(const Mesh& mesh) {
  check(mesh);
  double area = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) area += area_vector(mesh, t).norm() / 2;
  return area;
}

PointCloud sample_surface(const Mesh& mesh, std::size_t count, std::uint64_t seed) {
  check(mesh);
  std::vector<double> cumulative(mesh.triangles.size());
  double total = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    cumulative[t] = total += area_vector(mesh, t).norm();
  if (!(total > 0)) throw InputError("surface sampling: the mesh has no triangle of positive area");

  PointCloud cloud;
  cloud.points.reserve(count);
  cloud.normals.reserve(count);
  std::mt19937_64 rng(seed);
  for (std::size_t s = 0; s < count; ++s) {
    const double pick = uniform01(rng) * total;
    std::size_t t = std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin();
    t = std::min(t, cumulative.size() - 1);
    while (t > 0 && cumulative[t] == cumulative[t - 1]) --t;  // never a zero-area triangle
    // Uniform in the triangle: (1 - sqrt(u), sqrt(u) (1 - v), sqrt(u) v).
    const double su = std::sqrt(uniform01(rng)), v = uniform01(rng);
    const auto& tri = mesh.triangles[t];
    const Eigen::Vector3d a = mesh.positions[tri[0]].cast<double>();
    const Eigen::Vector3d b = mesh.positions[tri[1]].cast<double>();
    const Eigen::Vector3d c = mesh.positions[tri[2]].cast<double>();
    cloud.points.push_back(((1 - su) * a + su * (1 - v) * b + su * v * c).cast<float>());
    cloud.normals.push_back(area_vector(mesh, t).normalized().cast<float>());
  }
  return cloud;
}

}  // namespace binpick
