// The probes that tell a pose from its look-alikes (host/train/lookalike_probes.hpp): on the built-in
// plate, whose three half turns keep its outline, every probe lies on the plate where the
// turned plate has one of its holes, at least the margin inside it; parts without look-alikes
// have none; the file keeps them (version 4) and reads older files without them.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>

#include "host/core/error.hpp"
#include "host/train/lookalikes.hpp"
#include "host/train/ppf_model.hpp"
#include "host/train/ppf_model_file.hpp"
#include "host/train/lookalike_probes.hpp"
#include "synth/parts/builtin_parts.hpp"
#include "tests/support/test_device.hpp"
#include "tests/support/test_meshes.hpp"

namespace binpick {
namespace {

// The plate's holes (synth/parts/plate.cpp), in its own frame: 110 x 50 in x, y, 1.5 thick in z.
struct Hole {
  double x, y, half_length, radius;
};
constexpr Hole kHoles[] = {{-33, 7, 0, 8}, {2, -10, 7, 3.5}, {37, 12, 0, 3.25}};

// How far inside a hole (mm) the point (x, y) lies; negative outside every hole.
double inside_hole(double x, double y) {
  double best = -1e9;
  for (const Hole& h : kHoles) {
    const double cx = std::clamp(x, h.x - h.half_length, h.x + h.half_length);
    best = std::max(best, h.radius - std::hypot(x - cx, y - h.y));
  }
  return best;
}

PpfModel train(const Mesh& mesh) {
  return train_ppf_model(mesh, PpfTrainParams{}, nullptr, test::test_device());
}

TEST(LookalikeProbes, ThePlatesProbesLieWhereItsLookAlikesHaveHoles) {
  const PpfModel m = train(make_builtin_part("plate"));
  ASSERT_EQ(m.lookalikes.size(), 3u);
  ASSERT_EQ(m.probe_lookalike.size(), m.lookalike_probes.points.size());
  ASSERT_EQ(m.lookalike_probes.normals.size(), m.lookalike_probes.points.size());
  const float margin = kProbeMarginVoxels * m.voxel_size / kProbeVoxelDivisor;
  std::vector<std::size_t> per(3, 0);
  std::size_t walls = 0;
  for (std::size_t i = 0; i < m.lookalike_probes.points.size(); ++i) {
    const std::uint32_t s = m.probe_lookalike[i];
    ASSERT_LT(s, 3u);
    ++per[s];
    const Eigen::Vector3d p = m.lookalike_probes.points[i].cast<double>();
    // A wall, which the turned plate has elsewhere: a hole's, or the outline's where the
    // look-alike's turn (about the points' box centre and principal axes, which the holes move
    // by a fraction of a millimetre and degree) puts the turned end a little off. Seen edge on,
    // walls seldom count.
    if (std::fabs(m.lookalike_probes.normals[i].z()) < 0.1f) {
      const bool outline = std::fabs(p.x()) > 53.5 || std::fabs(p.y()) > 23.5;
      // (A voxel's mean of points on a round wall lies a little inside the circle.)
      if (!outline) {
        EXPECT_NEAR(inside_hole(p.x(), p.y()), 0.0, 0.5) << i << " at " << p.transpose();
      }
      ++walls;
      continue;
    }
    // Else on a face (both faces probe), on the plate's material, not in a hole.
    EXPECT_NEAR(std::fabs(p.z()), 0.75, 0.01) << i;
    EXPECT_NEAR(std::fabs(m.lookalike_probes.normals[i].z()), 1.0f, 1e-4f) << i;
    EXPECT_LT(inside_hole(p.x(), p.y()), 0.0) << i;
    // Turned back by the look-alike, it falls in a hole, the margin inside (less the
    // half-turn's centre offset from the outline's: under a millimetre).
    const Eigen::Vector3d q = m.lookalikes[s].inverse() * p;
    EXPECT_GT(inside_hole(q.x(), q.y()), margin - 1.0) << i;
  }
  // Every look-alike gets enough probes to average the noise out: the 16 mm hole alone holds
  // about 45 a face at 1.5 mm.
  for (std::size_t s = 0; s < 3; ++s) EXPECT_GE(per[s], 50u) << s;
  EXPECT_LT(walls, m.lookalike_probes.points.size() / 2);
  // The same mesh gives the same probes.
  const PpfModel again = train(make_builtin_part("plate"));
  EXPECT_EQ(again.lookalike_probes.points, m.lookalike_probes.points);
  EXPECT_EQ(again.probe_lookalike, m.probe_lookalike);
}

TEST(LookalikeProbes, PartsWithoutLookAlikesHaveNone) {
  const PpfModel box = train(test::box({80, 40, 20}));  // its half turns are exact symmetries
  EXPECT_TRUE(box.lookalikes.empty());
  EXPECT_TRUE(box.lookalike_probes.points.empty());
  const PpfModel l = train(test::l_bracket());
  EXPECT_TRUE(l.lookalikes.empty());
  EXPECT_TRUE(l.lookalike_probes.points.empty());
  // Degenerate inputs: no look-alikes, or no voxel.
  EXPECT_TRUE(find_lookalike_probes(test::l_bracket(), 2.7f, {}, test::test_device()).cloud.points.empty());
  EXPECT_TRUE(find_lookalike_probes(test::l_bracket(), 0.0f, {Eigen::Isometry3d::Identity()},
                               test::test_device())
                  .cloud.points.empty());
}

TEST(LookalikeProbes, TheModelFileKeepsThemAndOlderFilesReadWithout) {
  const PpfModel m = train(make_builtin_part("plate"));
  const std::string bytes = serialize_ppf_model(m);
  const PpfModel back = parse_ppf_model(bytes, "plate.ppfm");
  ASSERT_EQ(back.lookalikes.size(), m.lookalikes.size());
  for (std::size_t s = 0; s < m.lookalikes.size(); ++s)
    EXPECT_TRUE(back.lookalikes[s].isApprox(m.lookalikes[s], 1e-12));
  EXPECT_EQ(back.lookalike_probes.points, m.lookalike_probes.points);
  EXPECT_EQ(back.lookalike_probes.normals, m.lookalike_probes.normals);
  EXPECT_EQ(back.probe_lookalike, m.probe_lookalike);
  EXPECT_EQ(serialize_ppf_model(back), bytes);
  // Version 3: no probes; the look-alikes found again on the model's points, the same ones.
  const PpfModel old = parse_ppf_model(serialize_ppf_model(m, 3), "old.ppfm");
  EXPECT_TRUE(old.lookalike_probes.points.empty());
  ASSERT_EQ(old.lookalikes.size(), m.lookalikes.size());
  for (std::size_t s = 0; s < m.lookalikes.size(); ++s)
    EXPECT_TRUE(old.lookalikes[s].isApprox(m.lookalikes[s], 1e-9));
  // A probe naming a look-alike the file does not have, or a look-alike that is no rotation.
  PpfModel bad = m;
  bad.probe_lookalike.back() = 3;
  EXPECT_THROW(parse_ppf_model(serialize_ppf_model(bad), "bad.ppfm"), InputError);
  bad = m;
  bad.lookalikes[0].linear()(0, 0) = 2;
  EXPECT_THROW(parse_ppf_model(serialize_ppf_model(bad), "bad.ppfm"), InputError);
  // Cut inside the probes: truncated.
  EXPECT_THROW(parse_ppf_model(bytes.substr(0, bytes.size() - 10), "cut.ppfm"), InputError);
}

}  // namespace
}  // namespace binpick
