// A triangle mesh of a part, in millimetres; the common currency of loaders, synthesis and
// training.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace binpick {

struct Mesh {
  std::vector<Eigen::Vector3f> positions;               // mm
  std::vector<Eigen::Vector3f> normals;                 // unit, per vertex; empty if unknown
  std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise seen from outside
};

// A scene or model point cloud with unit normals (normals may be empty).
struct PointCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> normals;
};

// Appends from's points and normals to to's (the fit points followed by probes, for one pass).
inline void append_cloud(PointCloud& to, const PointCloud& from) {
  to.points.insert(to.points.end(), from.points.begin(), from.points.end());
  to.normals.insert(to.normals.end(), from.normals.begin(), from.normals.end());
}

}  // namespace binpick
