// L-bracket: a 36 long base plate and a 28 high upright plate, both 20 wide and 3 thick, each
// with a 7 mm hole. Unequal legs leave it without symmetry.
//
// Each plate is a strip of pieces along its length: plain rectangles and one square "hole
// cell" as wide as the plate. A cell's face is the ring between its square border and the hole,
// with border samples matched one to one to hole samples. The pieces next to a cell, the plate's
// side faces and the hole wall reuse the cell's border or hole points, so every edge is shared
// by exactly two faces.
#include <Eigen/Core>

#include "synth/parts/part_builder.hpp"
#include "synth/parts/part_shapes.hpp"

namespace binpick {
namespace {

constexpr double width = 20;  // along y, both plates
constexpr double half_width = width / 2;
constexpr double thickness = 3;
constexpr double base_length = 36;     // along x
constexpr double upright_height = 28;  // along z
constexpr double hole_radius = 3.5;
constexpr double base_hole_at = 22;     // x of the base hole centre
constexpr double upright_hole_at = 17;  // z of the upright hole centre
constexpr int samples_per_side = 12;    // border samples on each side of a hole cell

// Offsets of the border samples along one side of a cell, from -half_width to +half_width.
std::vector<double> side_offsets() {
  std::vector<double> d;
  for (int m = 0; m <= samples_per_side; ++m)
    d.push_back(-half_width + width * m / samples_per_side);
  return d;
}

// A plate in its own coordinates: u along its length, v along y (v in [-half_width,
// half_width]); to_3d places a (u, v) point on the face at depth w in [0, thickness].
struct Plate {
  Eigen::Vector3d (*to_3d)(double u, double v, double w);
  Eigen::Vector3d normal;  // of the face at w = thickness (the face at w = 0 faces the other way)
  double hole_at;
  double length;
};

Eigen::Vector3d base_point(double u, double v, double w) { return {u, v, w}; }
Eigen::Vector3d upright_point(double u, double v, double w) { return {w, v, u}; }

struct HoleCell {
  std::vector<Eigen::Vector2d> border;  // counter-clockwise in (u, v), starting at a corner
  std::vector<Eigen::Vector2d> hole;    // hole[k] is straight in from border[k]
};

HoleCell hole_cell(double centre) {
  const auto d = side_offsets();
  const int n = samples_per_side;
  HoleCell cell;
  for (int m = 0; m < n; ++m) cell.border.emplace_back(centre + half_width, d[m]);
  for (int m = 0; m < n; ++m) cell.border.emplace_back(centre + d[n - m], half_width);
  for (int m = 0; m < n; ++m) cell.border.emplace_back(centre - half_width, d[n - m]);
  for (int m = 0; m < n; ++m) cell.border.emplace_back(centre + d[m], -half_width);
  for (const auto& p : cell.border) {
    const Eigen::Vector2d c(centre, 0);
    cell.hole.push_back(c + hole_radius * (p - c).normalized());
  }
  return cell;
}

// The u positions, from the inner corner on, where the plate's faces have vertices along its
// long edges (v = +-half_width): piece boundaries and the cell's border samples.
std::vector<double> edge_stations(const Plate& plate) {
  std::vector<double> u{thickness};
  for (double d : side_offsets()) u.push_back(plate.hole_at + d);
  u.push_back(plate.length);
  return u;
}

// Both big faces of a plate (w = 0 from u = 0, w = thickness from u = thickness, where the
// other plate takes over), the hole wall, and the end face at u = length.
void add_plate(PartBuilder& b, const Plate& plate) {
  const HoleCell cell = hole_cell(plate.hole_at);
  const auto d = side_offsets();
  const double cell_start = plate.hole_at - half_width, cell_end = plate.hole_at + half_width;
  for (double w : {0.0, thickness}) {
    const Eigen::Vector3d n = w == 0 ? Eigen::Vector3d(-plate.normal) : plate.normal;
    auto at = [&](double u, double v) { return plate.to_3d(u, v, w); };
    if (w == 0)
      b.convex_polygon({at(0, -half_width), at(thickness, -half_width), at(thickness, half_width),
                        at(0, half_width)},
                       n);
    // Rectangle before the cell: its far edge carries the cell's left border samples.
    std::vector<Eigen::Vector3d> before{at(thickness, half_width), at(thickness, -half_width)};
    for (double v : d) before.push_back(at(cell_start, v));
    b.convex_polygon(before, n);
    std::vector<Eigen::Vector3d> after{at(plate.length, -half_width), at(plate.length, half_width)};
    for (auto v = d.rbegin(); v != d.rend(); ++v) after.push_back(at(cell_end, *v));
    b.convex_polygon(after, n);
    const std::size_t k = cell.border.size();
    for (std::size_t i = 0; i < k; ++i) {
      const auto& p = cell.border[i];
      const auto& q = cell.border[(i + 1) % k];
      b.quad(b.vertex(at(p.x(), p.y()), n), b.vertex(at(q.x(), q.y()), n),
             b.vertex(at(cell.hole[(i + 1) % k].x(), cell.hole[(i + 1) % k].y()), n),
             b.vertex(at(cell.hole[i].x(), cell.hole[i].y()), n));
    }
  }
  // Hole wall; its normals point into the hole, away from the material.
  const std::size_t k = cell.hole.size();
  const Eigen::Vector3d axis_point = plate.to_3d(plate.hole_at, 0, 0);
  auto wall_normal = [&](const Eigen::Vector2d& h) {
    return Eigen::Vector3d(axis_point - plate.to_3d(h.x(), h.y(), 0));
  };
  for (std::size_t i = 0; i < k; ++i) {
    const auto& h = cell.hole[i];
    const auto& g = cell.hole[(i + 1) % k];
    b.quad(b.vertex(plate.to_3d(h.x(), h.y(), 0), wall_normal(h)),
           b.vertex(plate.to_3d(g.x(), g.y(), 0), wall_normal(g)),
           b.vertex(plate.to_3d(g.x(), g.y(), thickness), wall_normal(g)),
           b.vertex(plate.to_3d(h.x(), h.y(), thickness), wall_normal(h)));
  }
  // End face.
  const Eigen::Vector3d end_normal = (plate.to_3d(1, 0, 0) - plate.to_3d(0, 0, 0));
  b.convex_polygon(
      {plate.to_3d(plate.length, -half_width, 0), plate.to_3d(plate.length, half_width, 0),
       plate.to_3d(plate.length, half_width, thickness),
       plate.to_3d(plate.length, -half_width, thickness)},
      end_normal);
}

// The two L-shaped side faces (y = +-half_width): the corner square, then a strip of quads
// along each plate between the same stations its big faces use.
void add_sides(PartBuilder& b, const Plate& base, const Plate& upright) {
  for (double v : {-half_width, half_width}) {
    const Eigen::Vector3d n(0, v, 0);
    b.convex_polygon({base.to_3d(0, v, 0), base.to_3d(thickness, v, 0),
                      base.to_3d(thickness, v, thickness), base.to_3d(0, v, thickness)},
                     n);
    for (const Plate* plate : {&base, &upright}) {
      const auto u = edge_stations(*plate);
      for (std::size_t i = 0; i + 1 < u.size(); ++i) {
        b.quad(b.vertex(plate->to_3d(u[i], v, 0), n), b.vertex(plate->to_3d(u[i + 1], v, 0), n),
               b.vertex(plate->to_3d(u[i + 1], v, thickness), n),
               b.vertex(plate->to_3d(u[i], v, thickness), n));
      }
    }
  }
}

}  // namespace

BuiltinShape make_bracket_shape() {
  const Plate base{&base_point, Eigen::Vector3d::UnitZ(), base_hole_at, base_length};
  const Plate upright{&upright_point, Eigen::Vector3d::UnitX(), upright_hole_at, upright_height};
  PartBuilder b;
  add_plate(b, base);
  add_plate(b, upright);
  add_sides(b, base, upright);
  return {b.build(), {}};
}

}  // namespace binpick
