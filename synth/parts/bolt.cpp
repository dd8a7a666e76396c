// Hex bolt, M10-like proportions: shank radius 5, 30 long with a 1 mm tip chamfer, head 16
// across flats and 6.5 high. The hex head limits its symmetry to sixfold about the axis.
#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "synth/parts/part_builder.hpp"
#include "synth/parts/part_shapes.hpp"

namespace binpick {
namespace {

constexpr int samples = 48;  // around the axis; a multiple of 6 so hex corners are samples
constexpr double shank_radius = 5;
constexpr double shank_length = 30;
constexpr double chamfer = 1;
constexpr double head_across_flats = 16;
constexpr double head_height = 6.5;

Eigen::Vector3d ring_point(int i, double radius, double z) {
  return binpick::ring_point(i, samples, radius, z);
}

// Hex corners sit at multiples of 60 degrees; sample i lies on the side between the corners
// around it, at the radius where its direction meets that side.
Eigen::Vector3d hex_point(int i, double z) {
  constexpr int per_side = samples / 6;
  i %= samples;  // sample `samples` is sample 0, bit for bit
  const double apothem = head_across_flats / 2;
  const int side = i / per_side;
  const double side_centre = (side + 0.5) * std::numbers::pi / 3;
  const double angle = 2 * std::numbers::pi * i / samples;
  return ring_point(i, apothem / std::cos(angle - side_centre), z);
}

Eigen::Vector3d hex_side_normal(int side) {
  const double angle = (side + 0.5) * std::numbers::pi / 3;
  return {std::cos(angle), std::sin(angle), 0};
}

}  // namespace

BuiltinShape make_bolt_shape() {
  PartBuilder b;
  const double tip_radius = shank_radius - chamfer;
  const double head_bottom = shank_length;
  const double head_top = shank_length + head_height;

  std::vector<Eigen::Vector3d> tip, head;
  for (int i = 0; i < samples; ++i) {
    tip.push_back(ring_point(i, tip_radius, 0));
    head.push_back(hex_point(i, head_top));
  }
  b.convex_polygon(tip, -Eigen::Vector3d::UnitZ());
  add_surface_of_revolution(b, samples, tip_radius, 0, shank_radius, chamfer);
  add_surface_of_revolution(b, samples, shank_radius, chamfer, shank_radius, head_bottom);

  // Underside of the head: the ring between the shank and the hexagon.
  const Eigen::Vector3d down = -Eigen::Vector3d::UnitZ();
  for (int i = 0; i < samples; ++i) {
    b.quad(b.vertex(ring_point(i, shank_radius, head_bottom), down),
           b.vertex(ring_point(i + 1, shank_radius, head_bottom), down),
           b.vertex(hex_point(i + 1, head_bottom), down),
           b.vertex(hex_point(i, head_bottom), down));
  }
  // Flat sides of the hexagon, each with its own normal.
  for (int i = 0; i < samples; ++i) {
    const Eigen::Vector3d n = hex_side_normal(i / (samples / 6));
    b.quad(b.vertex(hex_point(i, head_bottom), n), b.vertex(hex_point(i + 1, head_bottom), n),
           b.vertex(hex_point(i + 1, head_top), n), b.vertex(hex_point(i, head_top), n));
  }
  b.convex_polygon(head, Eigen::Vector3d::UnitZ());

  BuiltinShape shape{b.build(), {}};
  for (int k = 1; k < 6; ++k) {
    Eigen::Matrix4d rotation = Eigen::Matrix4d::Identity();
    rotation.topLeftCorner<3, 3>() =
        Eigen::AngleAxisd(k * std::numbers::pi / 3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    shape.symmetries.discrete.push_back(rotation);
  }
  return shape;
}

}  // namespace binpick
