// Equal tee pipe fitting: a run along x (outer radius 10, bore 7.5, 44 long) and a branch of
// the same radii along +z, 20 high from the run's axis. Two cylinders of equal radius meeting
// at right angles intersect in two plane ellipses (x = +-z), so the seam between run and
// branch is known exactly and both surfaces can share its points: run sample phi (angle about
// x, from +y towards +z) meets the branch at x = +-rho sin(phi), y = rho cos(phi),
// z = rho sin(phi).
#include <Eigen/Core>

#include "synth/parts/part_builder.hpp"
#include "synth/parts/part_shapes.hpp"

namespace binpick {
namespace {

constexpr int samples = 48;  // around each tube; a multiple of 4 so the seam ends are samples
constexpr double outer_radius = 10;
constexpr double bore_radius = 7.5;
constexpr double half_length = 22;
constexpr double branch_height = 20;

// Point of the run's cylinder of radius rho at sample i and axial position x.
Eigen::Vector3d run_point(double rho, int i, double x) {
  const Eigen::Vector2d d = unit_circle_point(i, samples);
  return {x, rho * d.x(), rho * d.y()};
}

// Where the branch cuts the run at sample i on the side of sign (+1 or -1); on the lower half
// (no branch) both sides meet at x = 0.
double seam_x(double rho, int i, double sign) {
  const double s = unit_circle_point(i, samples).y();
  return s > 0 ? sign * rho * s : 0.0;
}

// The branch's boundary on the run, as a closed loop of 2 * (samples / 2) seam points: the
// +x side from phi = 180 down to 0 degrees, then the -x side from 0 up to 180.
std::vector<Eigen::Vector3d> branch_seam(double rho) {
  std::vector<Eigen::Vector3d> loop;
  for (int i = samples / 2; i > 0; --i) loop.push_back(run_point(rho, i, seam_x(rho, i, +1)));
  for (int i = 0; i < samples / 2; ++i) loop.push_back(run_point(rho, i, seam_x(rho, i, -1)));
  return loop;
}

// One cylindrical wall of the run (outward = +1 for the outside, -1 for the bore).
void add_run_wall(PartBuilder& b, double rho, double outward) {
  for (int i = 0; i < samples; ++i) {
    auto normal = [&](int k) { return Eigen::Vector3d(run_point(outward, k, 0)); };
    for (double sign : {+1.0, -1.0}) {
      const double end = sign * half_length;
      b.quad(b.vertex(run_point(rho, i, seam_x(rho, i, sign)), normal(i)),
             b.vertex(run_point(rho, i, end), normal(i)),
             b.vertex(run_point(rho, i + 1, end), normal(i + 1)),
             b.vertex(run_point(rho, i + 1, seam_x(rho, i + 1, sign)), normal(i + 1)));
    }
  }
}

// One cylindrical wall of the branch, from the seam up to the top; each top point lies
// straight above its seam point.
void add_branch_wall(PartBuilder& b, double rho, double outward) {
  const auto seam = branch_seam(rho);
  for (std::size_t j = 0; j < seam.size(); ++j) {
    const auto& p = seam[j];
    const auto& q = seam[(j + 1) % seam.size()];
    const Eigen::Vector3d np = outward * Eigen::Vector3d(p.x(), p.y(), 0);
    const Eigen::Vector3d nq = outward * Eigen::Vector3d(q.x(), q.y(), 0);
    b.quad(b.vertex(p, np), b.vertex(q, nq), b.vertex({q.x(), q.y(), branch_height}, nq),
           b.vertex({p.x(), p.y(), branch_height}, np));
  }
}

}  // namespace

BuiltinShape make_tee_shape() {
  PartBuilder b;
  add_run_wall(b, outer_radius, +1);
  add_run_wall(b, bore_radius, -1);
  add_branch_wall(b, outer_radius, +1);
  add_branch_wall(b, bore_radius, -1);

  // Flat rings closing the wall at both ends of the run and at the top of the branch.
  for (double sign : {+1.0, -1.0}) {
    const Eigen::Vector3d n(sign, 0, 0);
    const double x = sign * half_length;
    for (int i = 0; i < samples; ++i) {
      b.quad(b.vertex(run_point(outer_radius, i, x), n),
             b.vertex(run_point(outer_radius, i + 1, x), n),
             b.vertex(run_point(bore_radius, i + 1, x), n),
             b.vertex(run_point(bore_radius, i, x), n));
    }
  }
  const auto outer_top = branch_seam(outer_radius), bore_top = branch_seam(bore_radius);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  auto top = [&](const Eigen::Vector3d& p) { return Eigen::Vector3d(p.x(), p.y(), branch_height); };
  for (std::size_t j = 0; j < outer_top.size(); ++j) {
    const std::size_t k = (j + 1) % outer_top.size();
    b.quad(b.vertex(top(outer_top[j]), up), b.vertex(top(outer_top[k]), up),
           b.vertex(top(bore_top[k]), up), b.vertex(top(bore_top[j]), up));
  }

  BuiltinShape shape{b.build(), {}};
  // Half a turn about the branch axis maps the run onto itself.
  shape.symmetries.discrete.push_back(Eigen::Vector4d(-1, -1, 1, 1).asDiagonal());
  return shape;
}

}  // namespace binpick
