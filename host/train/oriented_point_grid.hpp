// A uniform grid over points with normals, for the one question symmetry detection asks a
// million times: does the surface pass near this point, facing this way? Cells as wide as the
// search radius, so a query reads the 3 x 3 x 3 cells around its point; points are stored cell
// by cell (a counting sort in input order), so queries read memory in order and the same input
// gives the same grid.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "host/core/mesh.hpp"

namespace binpick {

// "Facing the same way" for the model's grids (look-alikes, look-alike and edge probes): normals
// within 30 degrees, cos 30.
inline constexpr float kSameFacingCos = 0.8660254037844386f;

class OrientedPointGrid {
 public:
  // cloud needs unit normals; radius > 0 (mm) is the largest distance a query looks at, and
  // min_cos the smallest cosine between a stored normal and the query's that still agrees.
  // The grid spans the cloud's bounding box; throws InputError if that box would need more than
  // kMaxCells cells of side radius.
  OrientedPointGrid(const PointCloud& cloud, float radius, float min_cos);

  static constexpr std::size_t kMaxCells = std::size_t(1) << 24;

  // Whether a stored point lies within radius of p with a normal agreeing with n.
  bool matches(const Eigen::Vector3f& p, const Eigen::Vector3f& n) const;

  // The distance from p to the tangent plane of the nearest stored point with an agreeing
  // normal within radius, or radius if there is none: a smooth measure of how well p lies on
  // the surface (the distance to the nearest sample alone is dominated by the sample spacing).
  float plane_distance(const Eigen::Vector3f& p, const Eigen::Vector3f& n) const;

  float radius() const { return radius_; }

 private:
  // Calls visit(point index) for the stored points in the cells around p, until it returns true;
  // p's own cell first if centre_first, else in memory order (the same order every time).
  template <class Visit>
  bool visit_near(const Eigen::Vector3f& p, bool centre_first, Visit&& visit) const;

  float radius_, min_cos_;
  Eigen::Vector3f lo_;
  std::int64_t dims_[3] = {0, 0, 0};
  std::vector<std::uint32_t> cell_start_;  // cells + 1, CSR over points_
  std::vector<Eigen::Vector3f> points_, normals_;
};

}  // namespace binpick
