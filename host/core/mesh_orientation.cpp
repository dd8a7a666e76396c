#include "host/core/mesh_orientation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "host/core/mesh_topology.hpp"

namespace binpick {
namespace {

using Triangle = std::array<std::uint32_t, 3>;

Eigen::Vector3d face_normal(const Mesh& mesh, const Triangle& t) {
  const Eigen::Vector3d a = mesh.positions[t[0]].cast<double>();
  const Eigen::Vector3d b = mesh.positions[t[1]].cast<double>();
  const Eigen::Vector3d c = mesh.positions[t[2]].cast<double>();
  return (b - a).cross(c - a);  // length: twice the area
}

// The signed volume the triangles enclose with their centroid (exact for a closed piece, and
// close for a nearly closed one such as a scan with a few holes), and their bounding box's.
std::pair<double, double> volumes(const Mesh& mesh, const std::vector<std::uint32_t>& faces) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  Eigen::AlignedBox3d box;
  for (std::uint32_t f : faces)
    for (std::uint32_t v : mesh.triangles[f]) {
      c += mesh.positions[v].cast<double>();
      box.extend(mesh.positions[v].cast<double>());
    }
  c /= 3.0 * double(faces.size());
  double v6 = 0;
  for (std::uint32_t f : faces) {
    const Triangle& t = mesh.triangles[f];
    const Eigen::Vector3d a = mesh.positions[t[0]].cast<double>() - c;
    const Eigen::Vector3d b = mesh.positions[t[1]].cast<double>() - c;
    const Eigen::Vector3d d = mesh.positions[t[2]].cast<double>() - c;
    v6 += a.dot(b.cross(d));
  }
  return {v6 / 6.0, box.volume()};
}

// A piece decides its own side by its volume only if it encloses a real share of its box: a
// flat or sliver piece (a scan artefact, a sheet) has a volume of rounding noise.
constexpr double kMinVolumeShare = 0.01;
// An open piece that still encloses this share of its box is nearly closed (a scan with holes).
constexpr double kNearlyClosedShare = 0.1;

void turn(Triangle& t) { std::swap(t[1], t[2]); }

struct EdgeUse {
  std::uint32_t face;
  bool forward;  // the face runs the edge from its smaller to its larger welded vertex
};

}  // namespace

OrientationReport orient_outward(Mesh& mesh) {
  OrientationReport report;
  const std::size_t nf = mesh.triangles.size();
  const std::vector<std::uint32_t> weld = first_index_at_same_position(mesh.positions);
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<EdgeUse>> edges;
  for (std::uint32_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = weld[mesh.triangles[f][k]], b = weld[mesh.triangles[f][(k + 1) % 3]];
      if (a == b) continue;
      edges[{std::min(a, b), std::max(a, b)}].push_back({f, a < b});
    }
  // Neighbours across manifold edges, with whether the two faces run the edge the same way.
  std::vector<std::vector<std::pair<std::uint32_t, bool>>> next(nf);
  std::vector<bool> open(nf, false);
  for (const auto& [edge, uses] : edges) {
    if (uses.size() == 1) open[uses[0].face] = true;
    if (uses.size() != 2) continue;
    const bool same = uses[0].forward == uses[1].forward;
    next[uses[0].face].push_back({uses[1].face, same});
    next[uses[1].face].push_back({uses[0].face, same});
  }
  // 1. Breadth first over each piece: a neighbour running a shared edge the same way is turned.
  std::vector<int> flipped(nf, -1);  // -1 unvisited, 0 kept, 1 turned
  const bool file_normals = mesh.normals.size() == mesh.positions.size();
  for (std::uint32_t seed = 0; seed < nf; ++seed) {
    if (flipped[seed] >= 0) continue;
    ++report.components;
    std::vector<std::uint32_t> piece = {seed};
    flipped[seed] = 0;
    bool piece_open = false;
    for (std::size_t i = 0; i < piece.size(); ++i) {
      const std::uint32_t f = piece[i];
      piece_open = piece_open || open[f];
      for (const auto& [g, same] : next[f]) {
        if (flipped[g] >= 0) continue;  // a Moebius strip keeps its seam
        flipped[g] = same ? 1 - flipped[f] : flipped[f];
        piece.push_back(g);
      }
    }
    for (std::uint32_t f : piece)
      if (flipped[f] == 1) turn(mesh.triangles[f]), ++report.made_consistent;
    // 2, 3. Which way round the whole piece goes.
    bool inside_out = false;
    const auto [volume, box] = volumes(mesh, piece);
    if (!piece_open) ++report.closed;
    if (std::fabs(volume) > (piece_open ? kNearlyClosedShare : kMinVolumeShare) * box) {
      inside_out = volume < 0;
    } else if (file_normals) {
      double agree = 0;
      for (std::uint32_t f : piece) {
        const Triangle& t = mesh.triangles[f];
        const Eigen::Vector3d n =
            (mesh.normals[t[0]] + mesh.normals[t[1]] + mesh.normals[t[2]]).cast<double>();
        agree += n.dot(face_normal(mesh, t)) >= 0 ? 1 : -1;
      }
      inside_out = agree < 0;
    } else {
      report.undecided += piece.size();
    }
    if (inside_out) {
      for (std::uint32_t f : piece) turn(mesh.triangles[f]);
      report.turned_out += piece.size();
    }
  }
  if (file_normals && nf > 0) {
    std::size_t disagree = 0;
    for (const Triangle& t : mesh.triangles) {
      const Eigen::Vector3d n =
          (mesh.normals[t[0]] + mesh.normals[t[1]] + mesh.normals[t[2]]).cast<double>();
      disagree += n.dot(face_normal(mesh, t)) < 0;
    }
    if (2 * disagree > nf) {
      for (auto& n : mesh.normals) n = -n;
      report.normals_flipped = true;
    }
  }
  return report;
}

}  // namespace binpick
