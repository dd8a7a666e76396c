// The edge probes of a part (host/train/edge_probes.hpp): on the built-in plate, every probe
// lies in free space at least the stated distance from the surface, either in the plane of one
// of its faces, facing the same way, just beyond its outline or inside a hole, or continuing a
// rim wall, each of its kind; a box gets probes around its faces' edges and none inside;
// the result is deterministic; the model file keeps them and their kinds (version 6), reads
// version 5 with every probe a face probe and version 4 without them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "host/core/error.hpp"
#include "host/train/edge_probes.hpp"
#include "host/train/oriented_point_grid.hpp"
#include "host/train/ppf_model.hpp"
#include "host/train/ppf_model_file.hpp"
#include "host/train/probe_surface.hpp"
#include "host/train/surface_sampling.hpp"
#include "synth/parts/builtin_parts.hpp"
#include "tests/support/test_device.hpp"
#include "tests/support/test_meshes.hpp"

namespace binpick {
namespace {

float margin_of(float voxel) { return kEdgeMarginVoxels * voxel / kProbeVoxelDivisor; }

// Whether any of a dense sample of the mesh lies within r of p.
bool near_surface(const OrientedPointGrid& any, const Eigen::Vector3f& p) {
  return any.matches(p, Eigen::Vector3f::UnitZ());
}

TEST(EdgeProbes, ThePlatesProbesContinueItsFacesJustBeyondTheEdges) {
  const Mesh plate = make_builtin_part("plate");
  const float voxel = 6.0f;  // 0.05 of its 120 mm diameter, as training's default
  const EdgeProbes found = find_edge_probes(plate, voxel, test::test_device());
  const PointCloud& probes = found.cloud;
  ASSERT_EQ(probes.normals.size(), probes.points.size());
  ASSERT_EQ(found.rim.size(), probes.points.size());
  ASSERT_GT(probes.points.size(), 300u);
  ASSERT_LE(probes.points.size(), kMaxEdgeProbes);
  const float margin = margin_of(voxel);
  // The outline's half sizes (about 55 x 25: the built-in part is scaled to its diameter).
  Eigen::Vector3f half = Eigen::Vector3f::Zero();
  for (const Eigen::Vector3f& v : plate.positions) half = half.cwiseMax(v.cwiseAbs());
  const float hx = half.x(), hy = half.y();
  // Free space: no surface within 0.7 margin (the probes keep 0.75), on a surface sample far
  // denser than the one the probes were found on.
  const OrientedPointGrid any(sample_surface(plate, 400000, 99), 0.7f * margin, -2.0f);
  std::size_t top = 0, inside_outline = 0, walls = 0, face_kind_in_faces = 0,
              rims_off_the_faces = 0;
  for (std::size_t i = 0; i < probes.points.size(); ++i) {
    const Eigen::Vector3f& p = probes.points[i];
    const Eigen::Vector3f& n = probes.normals[i];
    EXPECT_FALSE(near_surface(any, p)) << i << ": " << p.transpose();
    // A rim wall's probes continue it above or below the faces (or past a corner of the
    // outline), facing as the wall does: sideways.
    if (std::fabs(n.z()) < 1e-3f) {
      ++walls;
      const bool off_the_faces = std::fabs(p.z()) > 0.75f + 0.5f * margin;
      const bool past_a_corner = std::fabs(p.x()) > hx - margin && std::fabs(p.y()) > hy - margin;
      EXPECT_TRUE(off_the_faces || past_a_corner) << i << ": " << p.transpose();
      // Along the outline's sides a rim probe; only past a corner (continuing the wall along
      // its length, or where two walls meet) may one be a face probe.
      if (!found.rim[i]) {
        EXPECT_TRUE(past_a_corner) << i << ": " << p.transpose();
      }
      rims_off_the_faces += off_the_faces && found.rim[i];
      continue;
    }
    // Else in a face's plane (the faces at z = +-0.75), facing as that face does: a face probe
    // unless the face is narrower than a margin behind it (a bridge between holes).
    ASSERT_NEAR(std::fabs(n.z()), 1.0f, 1e-3f) << i;
    face_kind_in_faces += !found.rim[i];
    EXPECT_NEAR(p.z(), 0.75f * n.z(), 0.05f) << i;
    top += n.z() > 0;
    // Within a margin and a probe voxel of the outline.
    const float reach = margin + voxel / kProbeVoxelDivisor;
    EXPECT_LE(std::fabs(p.x()), hx + reach) << i;
    EXPECT_LE(std::fabs(p.y()), hy + reach) << i;
    inside_outline += std::fabs(p.x()) < hx - margin && std::fabs(p.y()) < hy - margin;
  }
  EXPECT_GT(walls, 0u);
  EXPECT_LT(walls, probes.points.size() / 2);
  EXPECT_GT(face_kind_in_faces, 9 * (probes.points.size() - walls) / 10);
  EXPECT_GT(rims_off_the_faces, walls / 2);
  // Both faces alike; the holes have their own probes.
  const std::size_t faces = probes.points.size() - walls;
  EXPECT_GT(top, faces / 3);
  EXPECT_LT(top, 2 * faces / 3);
  EXPECT_GT(inside_outline, 30u);
  // Deterministic.
  const EdgeProbes again = find_edge_probes(plate, voxel, test::test_device());
  EXPECT_EQ(again.cloud.points, probes.points);
  EXPECT_EQ(again.cloud.normals, probes.normals);
  EXPECT_EQ(again.rim, found.rim);
}

TEST(EdgeProbes, ABoxGetsThemAroundItsFacesAndNoneInside) {
  const Mesh box = test::box(Eigen::Vector3f(40, 30, 20));
  const float voxel = 2.5f;
  const EdgeProbes found = find_edge_probes(box, voxel, test::test_device());
  const PointCloud& probes = found.cloud;
  ASSERT_GT(probes.points.size(), 100u);
  // Every face of a box is broad: all face probes.
  EXPECT_EQ(found.rim, std::vector<std::uint8_t>(probes.points.size(), 0));
  const float margin = margin_of(voxel);
  for (std::size_t i = 0; i < probes.points.size(); ++i) {
    // Outside the box (from the origin to 40 x 30 x 20) by most of a margin, and by no more than one.
    const Eigen::Vector3f a = (probes.points[i] - Eigen::Vector3f(20, 15, 10)).cwiseAbs();
    const float out = (a - Eigen::Vector3f(20, 15, 10)).cwiseMax(0.0f).norm();
    EXPECT_GT(out, 0.7f * margin) << i << ": " << probes.points[i].transpose();
    EXPECT_LT(out, 1.01f * margin + 0.01f) << i;
  }
  EXPECT_TRUE(find_edge_probes(box, 0.0f, test::test_device()).cloud.points.empty());
}

// Reading `bytes` is refused as corrupt, for `what`.
void expect_corrupt(const std::string& bytes, const std::string& what) {
  try {
    parse_ppf_model(bytes, "bad.ppfm");
    ADD_FAILURE() << "read despite its " << what;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is corrupt (" + what + ")"), std::string::npos)
        << e.what();
  }
}

TEST(EdgeProbes, TheModelFileKeepsThemAndTheirKindsAndOlderVersionsReadAsTheyWere) {
  const PpfModel m = train_ppf_model(make_builtin_part("plate"), PpfTrainParams{}, nullptr,
                                     test::test_device());
  ASSERT_FALSE(m.edge_probes.points.empty());
  const std::string bytes = serialize_ppf_model(m);
  const PpfModel back = parse_ppf_model(bytes, "plate.ppfm");
  EXPECT_EQ(back.edge_probes.points, m.edge_probes.points);
  EXPECT_EQ(back.edge_probes.normals, m.edge_probes.normals);
  ASSERT_GT(m.edge_face_probes(), 0u);
  ASSERT_LT(m.edge_face_probes(), m.edge_probes.points.size());
  EXPECT_EQ(back.edge_probe_rim, m.edge_probe_rim);
  EXPECT_EQ(serialize_ppf_model(back), bytes);
  // Version 5: the same probes, all counted as face probes (as detection took them then).
  const PpfModel five = parse_ppf_model(serialize_ppf_model(m, 5), "five.ppfm");
  EXPECT_EQ(five.edge_probes.points, m.edge_probes.points);
  EXPECT_TRUE(five.edge_probe_rim.empty());
  EXPECT_EQ(five.edge_face_probes(), m.edge_probes.points.size());
  const PpfModel old = parse_ppf_model(serialize_ppf_model(m, 4), "old.ppfm");
  EXPECT_TRUE(old.edge_probes.points.empty());
  EXPECT_EQ(old.lookalike_probes.points, m.lookalike_probes.points);
  // A non-finite probe, an absurd count, a cut inside the probes.
  PpfModel bad = m;
  bad.edge_probes.normals[5].y() = std::nanf("");
  EXPECT_THROW(parse_ppf_model(serialize_ppf_model(bad), "bad.ppfm"), InputError);
  std::string huge = serialize_ppf_model(m, 6);  // the probes and their kinds last
  const std::size_t count_at = huge.size() - 25 * m.edge_probes.points.size() - 4;
  huge[count_at + 3] = 0x7f;
  expect_corrupt(huge, "edge probe count");
  EXPECT_THROW(parse_ppf_model(bytes.substr(0, bytes.size() - 10), "cut.ppfm"), InputError);
  // A kind that is neither face (0) nor rim (1).
  PpfModel odd = m;
  odd.edge_probe_rim.back() = 2;
  expect_corrupt(serialize_ppf_model(odd),
                 "edge probe kind " + std::to_string(m.edge_probes.points.size() - 1));
}

}  // namespace
}  // namespace binpick
