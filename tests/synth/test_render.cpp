// The bin renderer on real geometry (lavapipe, validation on): boxes at known poses must appear
// where the pinhole camera puts them, at the right depth, with consistent pixel counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <memory>

#include "host/core/error.hpp"
#include "synth/render/bin_renderer.hpp"

using namespace binpick;

namespace {
const bool validation_on = [] { return setenv("BINPICK_VK_VALIDATION", "1", 1) == 0; }();

const Eigen::Vector3d kHalf(20, 15, 10);  // the test box's half extents, mm

// A box with faces subdivided n x n (interior vertices to test), flat per-face normals,
// triangles counter-clockwise seen from outside.
Mesh make_box(const Eigen::Vector3d& half, int n) {
  Mesh m;
  const Eigen::Vector3f X = Eigen::Vector3f::UnitX(), Y = Eigen::Vector3f::UnitY(), Z = Eigen::Vector3f::UnitZ();
  const std::array<std::array<Eigen::Vector3f, 3>, 6> faces{{{X, Y, Z}, {-X, Z, Y}, {Y, Z, X},
                                                             {-Y, X, Z}, {Z, X, Y}, {-Z, Y, X}}};
  const Eigen::Vector3f h = half.cast<float>();
  for (const auto& [normal, u, v] : faces) {
    const auto base = std::uint32_t(m.positions.size());
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const float s = -1.0f + 2.0f * i / n, t = -1.0f + 2.0f * j / n;
        m.positions.push_back((normal + s * u + t * v).cwiseProduct(h));
        m.normals.push_back(normal);
      }
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::uint32_t a = base + j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
        m.triangles.push_back({a, b, c});
        m.triangles.push_back({a, c, d});
      }
  }
  return m;
}

Eigen::Isometry3d pose(double x, double y, double z, double angle_deg = 0,
                       Eigen::Vector3d axis = Eigen::Vector3d::UnitX()) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.linear() = Eigen::AngleAxisd(angle_deg * M_PI / 180, axis.normalized()).toRotationMatrix();
  p.translation() = Eigen::Vector3d(x, y, z);
  return p;
}

// Signed distance from a point in the box's frame to its surface.
double box_distance(const Eigen::Vector3d& p) {
  const Eigen::Vector3d q = p.cwiseAbs() - kHalf;
  return q.maxCoeff() <= 0 ? q.maxCoeff() : q.cwiseMax(0.0).norm();
}

// Parts 0 and 1 overlap (1 is nearer), 2 and 3 stand alone; 3 is axis-aligned on the axis.
std::vector<Eigen::Isometry3d> scene_poses() {
  return {pose(-100, -50, 850, 30, {1, 1, 0}), pose(-80, -40, 820, 50, {0, 1, 1}),
          pose(200, 120, 900, 70, {1, 0, 1}), pose(0, 0, 950)};
}

struct Fixture {
  Mesh box = make_box(kHalf, 6);
  RenderCamera camera = camera_for_bin();
  BinRenderer renderer{box, camera};
  RenderedBin scene = renderer.render(scene_poses());
};
Fixture& fixture() {
  static Fixture f;
  return f;
}

Eigen::Vector3d point_at(const RenderedBin& r, std::size_t i) {
  return {r.points[3 * i], r.points[3 * i + 1], r.points[3 * i + 2]};
}
}  // namespace

TEST(CameraForBin, ShowsTheWholeRim) {
  const RenderCamera c = camera_for_bin();
  EXPECT_EQ(c.width, 1600u);
  EXPECT_EQ(c.fx, c.fy);
  EXPECT_EQ(c.cx, 799.5);
  EXPECT_EQ(c.cy, 449.5);
  for (double sx : {-1.0, 1.0})
    for (double sy : {-1.0, 1.0}) {
      const Eigen::Vector2d uv = project(c, {sx * 300, sy * 200, 700});
      EXPECT_GT(uv.x(), 0);
      EXPECT_LT(uv.x(), 1599);
      EXPECT_GT(uv.y(), 0);
      EXPECT_LT(uv.y(), 899);
    }
  EXPECT_GT(project(c, {0, 200, 700}).y(), 890);  // the tight side is within 2 %
  EXPECT_LT(c.near_mm, 700);
  EXPECT_GT(c.far_mm, 1000);
  EXPECT_THROW(camera_for_bin(600, 400, 300, 250), InputError);
}

TEST(RenderBin, SurfacePointsLieOnTheirPart) {
  ASSERT_TRUE(validation_on);
  auto& f = fixture();
  const auto poses = scene_poses();
  std::size_t surface = 0;
  for (std::size_t i = 0; i < f.scene.instance.size(); ++i) {
    const int k = f.scene.instance[i];
    if (k < 0) continue;
    ++surface;
    ASSERT_LT(k, 4);
    const Eigen::Vector3d p = point_at(f.scene, i);
    ASSERT_NEAR(box_distance(poses[k].inverse() * p), 0.0, 0.05) << "pixel " << i << " part " << k;
    ASSERT_EQ(f.scene.depth_mm[i], f.scene.points[3 * i + 2]);
    const Eigen::Vector3d n(f.scene.normals[3 * i], f.scene.normals[3 * i + 1], f.scene.normals[3 * i + 2]);
    ASSERT_NEAR(n.norm(), 1.0, 1e-5);
    ASSERT_LT(n.dot(p), 0.0);
    ASSERT_GE(f.scene.gray[i], 51);
  }
  EXPECT_GT(surface, 4 * 3000u);
}

TEST(RenderBin, FaceCentreHasItsDepthAndNormal) {
  auto& f = fixture();
  // Part 3's -z face is the plane z = 940 facing the camera around pixel (800, 450).
  const std::size_t i = 450 * 1600 + 800;
  EXPECT_EQ(f.scene.instance[i], 3);
  EXPECT_NEAR(f.scene.depth_mm[i], 940.0, 0.01);
  EXPECT_NEAR(f.scene.points[3 * i], (800 - 799.5) * 940 / f.camera.fx, 1e-3);
  EXPECT_NEAR(f.scene.normals[3 * i + 2], -1.0, 1e-6);
  EXPECT_EQ(f.scene.gray[i], 255);
}

TEST(RenderBin, VerticesAreOnOrBehindTheSurface) {
  auto& f = fixture();
  const auto poses = scene_poses();
  int on = 0, seen = 0;
  for (std::size_t k = 0; k < poses.size(); ++k)
    for (const auto& vertex : f.box.positions) {
      const Eigen::Vector3d c = poses[k] * vertex.cast<double>();
      const Eigen::Vector2d uv = project(f.camera, c);
      const long u = std::lround(uv.x()), v = std::lround(uv.y());
      const std::size_t i = std::size_t(v) * 1600 + std::size_t(u);
      // Only where one surface covers the 3 x 3 pixels around: at a silhouette the nearest
      // pixel may show what lies behind the vertex's own part.
      bool one_surface = f.scene.instance[i] >= 0;
      for (long dv = -1; dv <= 1; ++dv)
        for (long du = -1; du <= 1; ++du)
          one_surface = one_surface && f.scene.instance[i + dv * 1600 + du] == f.scene.instance[i];
      if (!one_surface) continue;
      // The surface's plane at that pixel (flat faces: the face's plane), met along the
      // vertex's ray: the box's faces are convex, so the plane never lies behind the surface.
      const Eigen::Vector3d p = point_at(f.scene, i), ray = c / c.z();
      const Eigen::Vector3d n(f.scene.normals[3 * i], f.scene.normals[3 * i + 1], f.scene.normals[3 * i + 2]);
      if (std::abs(n.dot(ray.normalized())) < 0.2) continue;  // grazing: the plane is ill-defined
      ++seen;
      const double surface_z = n.dot(p) / n.dot(ray);
      EXPECT_GT(c.z(), surface_z - 0.05) << "part " << k << " vertex in front of the surface";
      if (std::abs(c.z() - surface_z) < 0.05 && f.scene.instance[i] == int(k)) ++on;
    }
  EXPECT_GT(seen, 300);
  EXPECT_GT(on, seen / 3);
}

TEST(RenderBin, PixelCentresAreAtIntegerCoordinates) {
  auto& f = fixture();
  // Box A's near face (z = 800) has its left edge at u = 50.75 and top edge at v = 40.75;
  // box B's has its right edge at u = 1500.25 and bottom edge at v = 850.25. Their side faces
  // project inside these edges (A is left of and above the axis, B right of and below).
  const RenderCamera& c = f.camera;
  const double z = 800;
  auto x_at = [&](double u) { return (u - c.cx) * z / c.fx; };
  auto y_at = [&](double v) { return (v - c.cy) * z / c.fy; };
  const auto a = pose(x_at(50.75) + kHalf.x(), y_at(40.75) + kHalf.y(), z + kHalf.z());
  const auto b = pose(x_at(1500.25) - kHalf.x(), y_at(850.25) - kHalf.y(), z + kHalf.z());
  const RenderedBin r = f.renderer.render({a, b}, {.count_unoccluded = false});
  auto at = [&](int u, int v) { return r.instance[std::size_t(v) * 1600 + u]; };
  const int a_row = int(std::lround(project(c, a.translation()).y()));
  const int a_col = int(std::lround(project(c, a.translation()).x()));
  EXPECT_EQ(at(51, a_row), 0);
  EXPECT_EQ(at(50, a_row), -1);
  EXPECT_EQ(at(a_col, 41), 0);
  EXPECT_EQ(at(a_col, 40), -1);
  const int b_row = int(std::lround(project(c, b.translation()).y()));
  const int b_col = int(std::lround(project(c, b.translation()).x()));
  EXPECT_EQ(at(1500, b_row), 1);
  EXPECT_EQ(at(1501, b_row), -1);
  EXPECT_EQ(at(b_col, 850), 1);
  EXPECT_EQ(at(b_col, 851), -1);
  EXPECT_TRUE(r.px_all.empty());
}

TEST(RenderBin, VisibleAndUnoccludedCounts) {
  auto& f = fixture();
  const RenderedBin& s = f.scene;
  ASSERT_EQ(s.px_visible.size(), 4u);
  ASSERT_EQ(s.px_all.size(), 4u);
  // px_visible and bbox_visible describe the instance image.
  std::vector<std::uint32_t> count(4, 0);
  std::vector<std::array<int, 4>> box(4, {1 << 30, 1 << 30, -1, -1});
  for (std::size_t i = 0; i < s.instance.size(); ++i)
    if (int k = s.instance[i]; k >= 0) {
      ++count[k];
      const int u = int(i % 1600), v = int(i / 1600);
      box[k] = {std::min(box[k][0], u), std::min(box[k][1], v), std::max(box[k][2], u), std::max(box[k][3], v)};
    }
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(s.px_visible[k], count[k]);
    EXPECT_EQ(s.bbox_visible[k], (std::array<int, 4>{box[k][0], box[k][1], box[k][2] - box[k][0], box[k][3] - box[k][1]}));
    EXPECT_LE(s.px_visible[k], s.px_all[k]);
    // px_all is what the part covers when rendered alone.
    const RenderedBin alone = f.renderer.render({scene_poses()[k]}, {.count_unoccluded = false});
    EXPECT_EQ(s.px_all[k], alone.px_visible[0]) << k;
    EXPECT_EQ(s.bbox_all[k], alone.bbox_visible[0]) << k;
  }
  EXPECT_LT(s.px_visible[0], s.px_all[0]);  // part 1 hides some of part 0
  EXPECT_EQ(s.px_visible[2], s.px_all[2]);  // alone in the scene
  EXPECT_EQ(s.px_visible[3], s.px_all[3]);
}

TEST(RenderBin, PartsOutsideTheViewHaveNoPixels) {
  auto& f = fixture();
  const RenderedBin r = f.renderer.render({pose(5000, 0, 900), pose(0, 0, 2000), pose(0, 0, 900)});
  EXPECT_EQ(r.px_visible[0], 0u);
  EXPECT_EQ(r.px_all[0], 0u);
  EXPECT_EQ(r.bbox_all[0], (std::array<int, 4>{-1, -1, -1, -1}));
  EXPECT_EQ(r.px_all[1], 0u);  // beyond the far plane
  EXPECT_GT(r.px_visible[2], 0u);
  EXPECT_EQ(r.px_visible[2], r.px_all[2]);
}

TEST(RenderBin, EmptySceneIsAllZero) {
  auto& f = fixture();
  const RenderedBin r = f.renderer.render({});
  EXPECT_EQ(r.width, 1600u);
  EXPECT_EQ(r.depth_mm.size(), 1600u * 900u);
  for (float d : r.depth_mm) ASSERT_EQ(d, 0.0f);
  for (float p : r.points) ASSERT_EQ(p, 0.0f);
  for (float n : r.normals) ASSERT_EQ(n, 0.0f);
  for (auto g : r.gray) ASSERT_EQ(g, 0);
  for (auto k : r.instance) ASSERT_EQ(k, -1);
  EXPECT_TRUE(r.px_visible.empty());
  EXPECT_TRUE(r.px_all.empty());
}

TEST(RenderBin, NoiseIsSeededAndAlongTheRay) {
  auto& f = fixture();
  const auto poses = scene_poses();
  const RenderedBin zero = f.renderer.render(poses, {.noise_sigma_mm = 0, .seed = 99, .count_unoccluded = false});
  EXPECT_EQ(zero.depth_mm, f.scene.depth_mm);  // sigma 0 is exactly the noiseless render
  EXPECT_EQ(zero.points, f.scene.points);
  const RenderOptions noisy{.noise_sigma_mm = 2.0, .seed = 7, .count_unoccluded = false};
  const RenderedBin a = f.renderer.render(poses, noisy), b = f.renderer.render(poses, noisy);
  EXPECT_EQ(a.depth_mm, b.depth_mm);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.instance, f.scene.instance);
  const RenderedBin c = f.renderer.render(poses, {.noise_sigma_mm = 2.0, .seed = 8, .count_unoccluded = false});
  EXPECT_NE(a.depth_mm, c.depth_mm);
  double sum2 = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.depth_mm.size(); ++i) {
    if (a.instance[i] < 0) continue;
    const double d = a.depth_mm[i] - f.scene.depth_mm[i];
    sum2 += d * d, ++n;
    // Same ray: the noisy point is the clean one scaled by the depth ratio.
    const double s = a.depth_mm[i] / f.scene.depth_mm[i];
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(a.points[3 * i + k], s * f.scene.points[3 * i + k], 1e-3);
  }
  EXPECT_NEAR(std::sqrt(sum2 / n), 2.0, 0.1);
}

TEST(RenderBin, CullingBackFacesChangesNothingForAClosedMesh) {
  auto& f = fixture();
  BinRenderer both_sides(f.box, f.camera, /*cull_back_faces=*/false);
  const RenderedBin r = both_sides.render(scene_poses());
  EXPECT_EQ(r.instance, f.scene.instance);
  EXPECT_EQ(r.depth_mm, f.scene.depth_mm);
  EXPECT_EQ(r.px_all, f.scene.px_all);
}

TEST(RenderBin, BadInputIsAClearError) {
  auto& f = fixture();
  EXPECT_THROW(BinRenderer(Mesh{}, f.camera), InputError);
  Eigen::Isometry3d bad = pose(0, 0, 900);
  bad.translation().x() = NAN;
  EXPECT_THROW(f.renderer.render({bad}), InputError);
  EXPECT_THROW(f.renderer.render({pose(0, 0, 900)}, {.noise_sigma_mm = -1}), InputError);
}
