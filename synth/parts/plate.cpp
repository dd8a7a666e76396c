// Sheet-metal plate, 110 x 50 and 1.5 thick (120 across), with a 16 mm hole, a 21 x 7 slot and
// a 6.5 mm hole. Thin and flat, unlike the other parts: it lies flat or leans in a pile and
// shows the camera little but its faces. The holes are placed so that no half turn maps the
// layout onto itself, so the plate has no symmetry (the mirror through its mid-plane maps it
// onto itself, but a mirror is not a pose).
//
// Each face is a row of pieces along x: a "hole cell" around each hole, a rectangle as high as
// the plate, and plain rectangles between the cells. A cell's face is the ring between its
// border and the hole, cut by rays from the hole's centre through the hole's own samples and
// through the cell's four corners: each ray gives one hole point and one border point, so each
// piece of the ring is a convex quad with its outer edge on one side of the cell. The plain
// rectangles, the rim walls and the hole wall reuse the cells' points, so every edge is shared
// by exactly two faces.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "synth/parts/part_builder.hpp"
#include "synth/parts/part_shapes.hpp"

namespace binpick {
namespace {

constexpr double half_length = 55;  // along x
constexpr double half_width = 25;   // along y
constexpr double thickness = 1.5;   // along z, from 0
constexpr int samples = 48;         // around a round hole; 24 along each end of the slot

// A round hole (half_length 0) or a slot along x: the points within radius of the segment from
// centre - (half_length, 0) to centre + (half_length, 0). The cell is its piece of the plate,
// x from cell_start to cell_end across the whole width.
struct Hole {
  Eigen::Vector2d centre;
  double half_length;
  double radius;
  double cell_start;
  double cell_end;
};

const Hole holes[] = {
    {{-33, 7}, 0, 8, -45, -21},   // 16 mm hole, up and to the left
    {{2, -10}, 7, 3.5, -12, 16},  // 21 x 7 slot, below the middle
    {{37, 12}, 0, 3.25, 31, 43},  // 6.5 mm hole, up and to the right
};

// The wall's normal at a point p of the hole's edge: into the hole, away from the material.
Eigen::Vector2d wall_normal(const Hole& hole, const Eigen::Vector2d& p) {
  const double x =
      std::clamp(p.x(), hole.centre.x() - hole.half_length, hole.centre.x() + hole.half_length);
  return (Eigen::Vector2d(x, hole.centre.y()) - p).normalized();
}

// The hole's edge counter-clockwise from its bottom: the right end's half circle, then the
// left one's (a round hole is both halves of one circle). The slot's straight sides run between
// the ends' last and first samples.
std::vector<Eigen::Vector2d> hole_samples(const Hole& hole) {
  const int quarter = samples / 4, last = hole.half_length > 0 ? quarter : quarter - 1;
  std::vector<Eigen::Vector2d> points;
  for (double side : {+1.0, -1.0}) {
    const Eigen::Vector2d end = hole.centre + Eigen::Vector2d(side * hole.half_length, 0);
    const int first = side > 0 ? -quarter : quarter;
    for (int i = first; i <= first + quarter + last; ++i)
      points.push_back(end + hole.radius * unit_circle_point(i, samples));
  }
  return points;
}

// Where the ray from the hole's centre along unit direction d leaves the hole.
Eigen::Vector2d hole_edge_towards(const Hole& hole, const Eigen::Vector2d& d) {
  if (d.y() != 0) {
    const double t = hole.radius / std::abs(d.y());
    if (std::abs(t * d.x()) <= hole.half_length) return hole.centre + t * d;
  }
  const Eigen::Vector2d end(d.x() >= 0 ? hole.half_length : -hole.half_length, 0);
  const double along = d.dot(end);
  const double t = along + std::sqrt(along * along - end.squaredNorm() + hole.radius * hole.radius);
  return hole.centre + t * d;
}

// Where the ray from the hole's centre through p leaves the cell, exactly on its side.
Eigen::Vector2d cell_border_towards(const Hole& hole, const Eigen::Vector2d& p) {
  const Eigen::Vector2d d = p - hole.centre;
  const double x = d.x() > 0 ? hole.cell_end : hole.cell_start;
  const double y = d.y() > 0 ? half_width : -half_width;
  const double tx = (x - hole.centre.x()) / d.x(), ty = (y - hole.centre.y()) / d.y();
  if (d.y() == 0 || (d.x() != 0 && tx < ty)) return {x, hole.centre.y() + tx * d.y()};
  return {hole.centre.x() + ty * d.x(), y};
}

// One ray of a cell: its point on the hole's edge (with the wall's normal there) and on the
// cell's border.
struct Ray {
  double angle;
  Eigen::Vector2d hole;
  Eigen::Vector2d border;
};

// The cell's rays counter-clockwise.
std::vector<Ray> cell_rays(const Hole& hole) {
  std::vector<Ray> rays;
  auto angle_of = [&](const Eigen::Vector2d& p) {
    const Eigen::Vector2d d = p - hole.centre;
    return std::atan2(d.y(), d.x());
  };
  for (const auto& p : hole_samples(hole))
    rays.push_back({angle_of(p), p, cell_border_towards(hole, p)});
  for (double x : {hole.cell_start, hole.cell_end}) {
    for (double y : {-half_width, half_width}) {
      const Eigen::Vector2d corner(x, y);
      rays.push_back(
          {angle_of(corner), hole_edge_towards(hole, (corner - hole.centre).normalized()), corner});
    }
  }
  std::sort(rays.begin(), rays.end(), [](const Ray& a, const Ray& b) { return a.angle < b.angle; });
  return rays;
}

Eigen::Vector3d at(const Eigen::Vector2d& p, double z) { return {p.x(), p.y(), z}; }

// The cells' border points on the line x = x, bottom to top.
std::vector<Eigen::Vector2d> points_at_x(const std::vector<std::vector<Ray>>& cells, double x) {
  std::vector<Eigen::Vector2d> points;
  for (const auto& rays : cells) {
    for (const auto& ray : rays)
      if (ray.border.x() == x) points.push_back(ray.border);
  }
  std::sort(points.begin(), points.end(),
            [](const auto& a, const auto& b) { return a.y() < b.y(); });
  return points;
}

// A face (z = 0 facing down or z = thickness facing up): the rectangles between the cells and
// the rings of the cells.
void add_face(PartBuilder& b, const std::vector<std::vector<Ray>>& cells, double z) {
  const Eigen::Vector3d n(0, 0, z == 0 ? -1 : 1);
  // Rectangles from each cell's end (or the plate's) to the next cell's start (or the plate's).
  std::vector<double> gaps{-half_length};
  for (const auto& hole : holes) {
    gaps.push_back(hole.cell_start);
    gaps.push_back(hole.cell_end);
  }
  gaps.push_back(half_length);
  for (std::size_t g = 0; g < gaps.size(); g += 2) {
    auto left = points_at_x(cells, gaps[g]), right = points_at_x(cells, gaps[g + 1]);
    if (left.empty()) left = {{gaps[g], -half_width}, {gaps[g], half_width}};
    if (right.empty()) right = {{gaps[g + 1], -half_width}, {gaps[g + 1], half_width}};
    std::vector<Eigen::Vector3d> boundary;
    for (const auto& p : right) boundary.push_back(at(p, z));
    for (auto p = left.rbegin(); p != left.rend(); ++p) boundary.push_back(at(*p, z));
    b.convex_polygon(boundary, n);
  }
  for (const auto& rays : cells) {
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const Ray& r = rays[i];
      const Ray& s = rays[(i + 1) % rays.size()];
      b.quad(b.vertex(at(r.border, z), n), b.vertex(at(s.border, z), n), b.vertex(at(s.hole, z), n),
             b.vertex(at(r.hole, z), n));
    }
  }
}

void add_hole_wall(PartBuilder& b, const Hole& hole, const std::vector<Ray>& rays) {
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Eigen::Vector2d p = rays[i].hole, q = rays[(i + 1) % rays.size()].hole;
    const Eigen::Vector3d np = at(wall_normal(hole, p), 0), nq = at(wall_normal(hole, q), 0);
    b.quad(b.vertex(at(p, 0), np), b.vertex(at(q, 0), nq), b.vertex(at(q, thickness), nq),
           b.vertex(at(p, thickness), np));
  }
}

// The outline's walls. The long sides are cut wherever the faces have a vertex on them: the
// plate's corners and the cells' border points.
void add_rim(PartBuilder& b, const std::vector<std::vector<Ray>>& cells) {
  for (double y : {-half_width, half_width}) {
    std::vector<double> stations{-half_length, half_length};
    for (const auto& rays : cells) {
      for (const auto& ray : rays)
        if (ray.border.y() == y) stations.push_back(ray.border.x());
    }
    std::sort(stations.begin(), stations.end());
    const Eigen::Vector3d n(0, y, 0);
    for (std::size_t i = 0; i + 1 < stations.size(); ++i) {
      const Eigen::Vector2d p(stations[i], y), q(stations[i + 1], y);
      b.quad(b.vertex(at(p, 0), n), b.vertex(at(q, 0), n), b.vertex(at(q, thickness), n),
             b.vertex(at(p, thickness), n));
    }
  }
  for (double x : {-half_length, half_length}) {
    const Eigen::Vector2d p(x, -half_width), q(x, half_width);
    b.convex_polygon({at(p, 0), at(q, 0), at(q, thickness), at(p, thickness)},
                     Eigen::Vector3d(x, 0, 0));
  }
}

}  // namespace

BuiltinShape make_plate_shape() {
  std::vector<std::vector<Ray>> cells;
  for (const auto& hole : holes) cells.push_back(cell_rays(hole));
  PartBuilder b;
  for (double z : {0.0, thickness}) add_face(b, cells, z);
  for (std::size_t h = 0; h < cells.size(); ++h) add_hole_wall(b, holes[h], cells[h]);
  add_rim(b, cells);
  return {b.build(), {}};
}

}  // namespace binpick
