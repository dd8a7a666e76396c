#include "synth/physics/mass_properties.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "host/core/error.hpp"

namespace binpick {

MassProperties mass_properties(const Mesh& mesh) {
  if (mesh.positions.empty() || mesh.triangles.empty())
    throw InputError("cannot compute the mass of an empty mesh");
  // Integrate relative to a point inside the bounding box: far from the origin the
  // tetrahedra's large opposite volumes would cancel away the precision.
  Eigen::Vector3d lo = mesh.positions.front().cast<double>(), hi = lo;
  for (const auto& p : mesh.positions) {
    lo = lo.cwiseMin(p.cast<double>());
    hi = hi.cwiseMax(p.cast<double>());
  }
  const Eigen::Vector3d ref = 0.5 * (lo + hi);

  // Each triangle and `ref` span a signed tetrahedron (divergence theorem):
  // volume a.(b x c)/6, first moment volume (a+b+c)/4,
  // second moment volume/20 (aa' + bb' + cc' + (a+b+c)(a+b+c)').
  double volume = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.positions.at(t[0]).cast<double>() - ref;
    const Eigen::Vector3d b = mesh.positions.at(t[1]).cast<double>() - ref;
    const Eigen::Vector3d c = mesh.positions.at(t[2]).cast<double>() - ref;
    const double v = a.dot(b.cross(c)) / 6.0;
    const Eigen::Vector3d s = a + b + c;
    volume += v;
    first += v * s / 4.0;
    second +=
        v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  // Inside-out winding flips every integral's sign alike.
  if (volume < 0.0) {
    volume = -volume;
    first = -first;
    second = -second;
  }
  const double box_volume = (hi - lo).prod();
  if (!(volume > 1e-9 * box_volume) || !std::isfinite(volume))
    throw InputError("part mesh encloses no volume (is it closed?)");

  const Eigen::Vector3d centroid = first / volume;
  const Eigen::Matrix3d covariance = second / volume - centroid * centroid.transpose();
  const Eigen::Matrix3d inertia =
      covariance.trace() * Eigen::Matrix3d::Identity() - covariance;  // per unit mass
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(inertia);
  Eigen::Matrix3d axes = eigen.eigenvectors();
  if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);  // a rotation, not a reflection

  MassProperties props;
  props.volume = volume;
  props.principal_frame = Eigen::Isometry3d::Identity();
  props.principal_frame.linear() = axes;
  props.principal_frame.translation() = ref + centroid;
  props.inertia_per_mass = eigen.eigenvalues();
  return props;
}

}  // namespace binpick
