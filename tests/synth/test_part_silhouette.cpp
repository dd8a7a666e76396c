// Each part drawn alone (the atlas pass with its depth attachment, lavapipe) against the plain
// C++ rasteriser part_silhouette_reference, on random poses of a concave part. Integer results
// (which pixels) must agree exactly except for pixel centres within 1/64 pixel of a projected
// triangle edge (the two sides round vertex positions and break edge ties independently);
// depths must agree within 0.1 mm, one depth PNG unit (lavapipe's float plane equation for the z-buffer value and
// float equation 1 against double 1/z interpolation; measured up to 0.052 mm at 850 mm, on
// surfaces seen at grazing angles)
// wherever both cover a pixel away from such an edge.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <map>
#include <random>

#include "host/core/error.hpp"
#include "host/core/mesh_normals.hpp"
#include "synth/render/bin_renderer.hpp"
#include "synth/render/part_silhouette.hpp"
#include "tests/support/test_meshes.hpp"

using namespace binpick;

namespace {

Mesh torus_with_normals() {
  Mesh m = test::torus();
  compute_crease_normals(m);
  return m;
}

// Distance in pixels from pixel p's centre to the nearest projected edge of the part.
double edge_distance(const Mesh& mesh, const Eigen::Isometry3d& pose, const RenderCamera& cam,
                     std::uint32_t p) {
  const Eigen::Vector2d c(double(p % cam.width), double(p / cam.width));
  double best = INFINITY;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d a = project(cam, pose * mesh.positions[t[k]].cast<double>());
      const Eigen::Vector2d b = project(cam, pose * mesh.positions[t[(k + 1) % 3]].cast<double>());
      const Eigen::Vector2d ab = b - a;
      const double s = std::clamp((c - a).dot(ab) / std::max(ab.squaredNorm(), 1e-12), 0.0, 1.0);
      best = std::min(best, (a + s * ab - c).norm());
    }
  return best;
}

std::vector<Eigen::Isometry3d> random_poses(int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < n; ++i) {
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    p.linear() = Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized())
                     .toRotationMatrix();
    // Inside the bin camera's view, some beyond the image's border (truncated).
    p.translation() = Eigen::Vector3d(400 * u(rng), 250 * u(rng), 850 + 100 * u(rng));
    poses.push_back(p);
  }
  return poses;
}

}  // namespace

TEST(PartSilhouette, AtlasPassMatchesReferenceOnRandomPoses) {
  const Mesh torus = torus_with_normals();
  const RenderCamera camera = camera_for_bin();
  BinRenderer renderer(torus, camera);
  const auto poses = random_poses(40, 7);
  const RenderedBin r = renderer.render(poses, {.silhouettes = true});
  ASSERT_EQ(r.silhouettes.size(), poses.size());
  std::size_t compared = 0, edge_mismatches = 0;
  double max_diff = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const PartSilhouette& gpu = r.silhouettes[i];
    const PartSilhouette ref = part_silhouette_reference(torus, poses[i], camera, true);
    ASSERT_EQ(gpu.pixels.size(), gpu.depth_mm.size());
    ASSERT_TRUE(std::is_sorted(gpu.pixels.begin(), gpu.pixels.end()));
    EXPECT_EQ(gpu.pixels.size(), r.px_all[i]) << i;  // the same pass counts px_all
    std::map<std::uint32_t, float> want;
    for (std::size_t k = 0; k < ref.pixels.size(); ++k) want[ref.pixels[k]] = ref.depth_mm[k];
    std::map<std::uint32_t, float> got;
    for (std::size_t k = 0; k < gpu.pixels.size(); ++k) got[gpu.pixels[k]] = gpu.depth_mm[k];
    for (const auto& [p, z] : got) {
      const auto it = want.find(p);
      const bool on_edge = edge_distance(torus, poses[i], camera, p) < 1.0 / 64;
      if (it == want.end()) {
        EXPECT_TRUE(on_edge) << "part " << i << " pixel " << p << " only on the GPU";
        edge_mismatches += 1;
        continue;
      }
      if (!on_edge) {
        EXPECT_NEAR(z, it->second, 0.1) << "part " << i << " pixel " << p;
        max_diff = std::max(max_diff, std::abs(double(z) - double(it->second)));
      }
      ++compared;
    }
    for (const auto& [p, z] : want)
      if (!got.count(p)) {
        EXPECT_LT(edge_distance(torus, poses[i], camera, p), 1.0 / 64)
            << "part " << i << " pixel " << p << " only in the reference";
        edge_mismatches += 1;
      }
  }
  std::printf("%zu pixels compared, %zu edge mismatches, depths within %.4f mm\n", compared,
              edge_mismatches, max_diff);
  EXPECT_GT(compared, 10000u);
  EXPECT_LT(edge_mismatches * 1000, compared);  // edge ties are rare
}

TEST(PartSilhouette, AnUnoccludedPartHasTheSceneDepth) {
  // One part alone: its silhouette is the scene's surface pixel for pixel (the same rasteriser,
  // shifted by whole pixels), its depth the same within the plane equation's rounding.
  const Mesh torus = torus_with_normals();
  BinRenderer renderer(torus, camera_for_bin());
  const auto poses = random_poses(1, 3);
  const RenderedBin r = renderer.render(poses, {.silhouettes = true});
  const PartSilhouette& s = r.silhouettes[0];
  ASSERT_GT(s.pixels.size(), 100u);
  std::size_t surface = 0;
  for (float d : r.depth_mm) surface += d > 0;
  EXPECT_EQ(surface, s.pixels.size());
  for (std::size_t k = 0; k < s.pixels.size(); ++k)
    ASSERT_NEAR(r.depth_mm[s.pixels[k]], s.depth_mm[k], 0.05) << s.pixels[k];
}

TEST(PartSilhouette, NeedsTheUnoccludedPass) {
  BinRenderer renderer(torus_with_normals(), camera_for_bin());
  EXPECT_THROW(renderer.render(random_poses(1, 1), {.count_unoccluded = false, .silhouettes = true}),
               InputError);
}
