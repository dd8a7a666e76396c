// Stepped shaft, 60 long and 13 across at its widest (4.6 : 1): a chamfered journal of
// diameter 8, a seat of 11, a collar of 13 and a chamfered end of 10. A long thin part that is
// round: a pose can only be known up to a turn about its axis. The steps differ from one end to
// the other, so no half turn swaps the ends and the axis is its only symmetry.
#include <Eigen/Core>
#include <iterator>
#include <vector>

#include "synth/parts/part_builder.hpp"
#include "synth/parts/part_shapes.hpp"

namespace binpick {
namespace {

constexpr int samples = 48;  // around the axis, as the bolt
constexpr double half_length = 30;

// The profile (radius, z) from the bottom end's rim to the top end's rim; each segment sweeps
// one band about the z axis: a chamfer cone, a cylinder, or a flat shoulder between two steps.
struct ProfilePoint {
  double r;
  double z;
};
constexpr ProfilePoint profile[] = {
    {3.2, -half_length},
    {4.0, -29.2},  // 0.8 chamfer
    {4.0, -16},
    {5.5, -16},  // journal, diameter 8 and 14 long; shoulder
    {5.5, 2},
    {6.5, 2},  // seat, diameter 11 and 18 long; shoulder
    {6.5, 12},
    {5.0, 12},  // collar, diameter 13 and 10 long; shoulder
    {5.0, 29.5},
    {4.5, half_length},  // end, diameter 10; 0.5 chamfer
};

}  // namespace

BuiltinShape make_shaft_shape() {
  PartBuilder b;
  constexpr std::size_t n = std::size(profile);
  std::vector<Eigen::Vector3d> bottom, top;
  for (int i = 0; i < samples; ++i) {
    bottom.push_back(ring_point(i, samples, profile[0].r, profile[0].z));
    top.push_back(ring_point(i, samples, profile[n - 1].r, profile[n - 1].z));
  }
  b.convex_polygon(bottom, -Eigen::Vector3d::UnitZ());
  for (std::size_t k = 0; k + 1 < n; ++k)
    add_surface_of_revolution(b, samples, profile[k].r, profile[k].z, profile[k + 1].r,
                              profile[k + 1].z);
  b.convex_polygon(top, Eigen::Vector3d::UnitZ());

  BuiltinShape shape{b.build(), {}};
  shape.symmetries.continuous.push_back({Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero()});
  return shape;
}

}  // namespace binpick
