#include "synth/decompose/hacd_simplify.hpp"

#include <cstdint>
#include <stdexcept>

#include <meshoptimizer.h>

namespace binpick {
namespace {

// Relative to the mesh's extent: the deformation the topology-keeping pass may make. The hulls
// are grown to cover the original mesh within 1 % of its diagonal afterwards anyway.
constexpr float kMaxDeformation = 0.02f;

}  // namespace

HacdMesh simplify_for_hacd(const HacdMesh& mesh, std::size_t limit, std::size_t target) {
  if (target == 0 || target > limit)
    throw std::invalid_argument("simplify_for_hacd: the target must be in [1, limit]");
  if (mesh.triangles.size() <= limit) return mesh;
  std::vector<float> xyz;
  xyz.reserve(3 * mesh.points.size());
  for (const auto& p : mesh.points) xyz.insert(xyz.end(), {float(p.x()), float(p.y()), float(p.z())});
  std::vector<unsigned> indices;
  indices.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (long i : t) indices.push_back(unsigned(i));
  std::vector<unsigned> out(indices.size());
  const std::size_t wanted = 3 * target;
  std::size_t n = meshopt_simplify(out.data(), indices.data(), indices.size(), xyz.data(),
                                   mesh.points.size(), 3 * sizeof(float), wanted, kMaxDeformation,
                                   0, nullptr);
  if (n > wanted) {
    out.resize(n);
    std::vector<unsigned> coarser(n);
    n = meshopt_simplifySloppy(coarser.data(), out.data(), out.size(), xyz.data(),
                               mesh.points.size(), 3 * sizeof(float), wanted, 1.0f, nullptr);
    coarser.resize(n);
    out = std::move(coarser);
  }
  out.resize(n);
  // Keep the points the triangles still use, in their first use's order.
  HacdMesh simple;
  std::vector<long> remap(mesh.points.size(), -1);
  for (std::size_t k = 0; k + 2 < out.size(); k += 3) {
    std::array<long, 3> t{};
    for (int c = 0; c < 3; ++c) {
      long& r = remap[out[k + c]];
      if (r < 0) {
        r = long(simple.points.size());
        simple.points.push_back(mesh.points[out[k + c]]);
      }
      t[c] = r;
    }
    if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) simple.triangles.push_back(t);
  }
  // A mesh the simplifier could not keep a solid of (nothing left) goes to HACD as it is.
  return simple.triangles.size() >= 4 ? simple : mesh;
}

}  // namespace binpick
