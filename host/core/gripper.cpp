#include "host/core/gripper.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

namespace binpick {

double signed_distance(const GripperSolid& s, const Eigen::Vector3d& p) {
  const Eigen::Vector3d q = p - s.centre;
  Eigen::Vector2d out;  // (across, along z) distances beyond the surface, negative inside
  if (s.shape == GripperSolid::Shape::cylinder) {
    out = {std::hypot(q.x(), q.y()) - s.half.x(), std::abs(q.z()) - s.half.z()};
  } else {
    const Eigen::Vector3d d = q.cwiseAbs() - s.half;
    const double outside = d.cwiseMax(0.0).norm();
    return outside > 0 ? outside : d.maxCoeff();
  }
  const double outside = out.cwiseMax(0.0).norm();
  return outside > 0 ? outside : out.maxCoeff();
}

std::vector<Eigen::Vector3d> surface_samples(const GripperSolid& s) {
  std::vector<Eigen::Vector3d> out;
  if (s.shape == GripperSolid::Shape::cylinder) {
    for (const double z : {-s.half.z(), s.half.z()}) {
      out.push_back(s.centre + Eigen::Vector3d(0, 0, z));
      for (int k = 0; k < 16; ++k) {
        const double a = 2 * std::numbers::pi * k / 16;
        out.push_back(s.centre + Eigen::Vector3d(s.half.x() * std::cos(a), s.half.x() * std::sin(a), z));
      }
    }
    return out;
  }
  for (int k = 0; k < 8; ++k)
    out.push_back(s.centre + Eigen::Vector3d((k & 1 ? 1 : -1) * s.half.x(), (k & 2 ? 1 : -1) * s.half.y(),
                                             (k & 4 ? 1 : -1) * s.half.z()));
  for (int a = 0; a < 3; ++a)
    for (const double sign : {-1.0, 1.0}) {
      Eigen::Vector3d p = s.centre;
      p[a] += sign * s.half[a];
      out.push_back(p);
    }
  return out;
}

Gripper Gripper::suction(double cup_diameter, double standoff, double body_diameter,
                         double body_length) {
  return {Grasp::Kind::suction, cup_diameter, standoff, body_diameter, body_length};
}

Gripper Gripper::parallel(double finger_width, double finger_depth, double finger_length,
                          double palm_height) {
  return {Grasp::Kind::parallel, finger_width, finger_depth, finger_length, palm_height};
}

std::vector<GripperSolid> Gripper::solids(const Grasp& grasp) const {
  if (grasp.kind != kind) throw std::logic_error("Gripper::solids: a grasp of another kind");
  using S = GripperSolid::Shape;
  if (kind == Grasp::Kind::suction)  // the cup from the surface up, the body above it
    return {{S::cylinder, {0, 0, -b / 2}, {a / 2, a / 2, b / 2}},
            {S::cylinder, {0, 0, -b - d / 2}, {c / 2, c / 2, d / 2}}};
  // Fingers beside the opening, their tips a quarter of their length past the grasp point; the
  // palm across both above them.
  const double x = grasp.size / 2 + a / 2, z = -c / 4;
  return {{S::box, {x, 0, z}, {a / 2, b / 2, c / 2}},
          {S::box, {-x, 0, z}, {a / 2, b / 2, c / 2}},
          {S::box, {0, 0, -3 * c / 4 - d / 2}, {grasp.size / 2 + a, b / 2, d / 2}}};
}

double Gripper::length() const { return kind == Grasp::Kind::suction ? b + d : 3 * c / 4 + d; }

std::string Gripper::describe() const {
  return kind == Grasp::Kind::suction
             ? fmt::format("suction:{:g},{:g},{:g},{:g}", a, b, c, d)
             : fmt::format("parallel:{:g},{:g},{:g},{:g}", a, b, c, d);
}

std::string bin_contact(const std::vector<GripperSolid>& solids,
                        const Eigen::Isometry3d& grasp_in_frame, const Eigen::Matrix3d& axes,
                        const Eigen::Vector3d& origin, const Eigen::Vector3d& interior,
                        double tolerance) {
  bool wall = false, floor = false;
  for (const GripperSolid& s : solids)
    for (const Eigen::Vector3d& q : surface_samples(s)) {
      const Eigen::Vector3d b = axes.transpose() * (grasp_in_frame * q - origin);
      if (b.z() < -tolerance) floor = true;
      if (b.z() < interior.z() && (std::abs(b.x()) > interior.x() / 2 + tolerance ||
                                   std::abs(b.y()) > interior.y() / 2 + tolerance))
        wall = true;
    }
  if (wall) return "the bin's wall";
  return floor ? "the bin's floor" : "";
}

Gripper default_suction_gripper(double part_diameter, double cup_diameter) {
  return Gripper::suction(cup_diameter, 0.1 * part_diameter, cup_diameter, 2 * part_diameter);
}

}  // namespace binpick
