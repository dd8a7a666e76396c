// Absurd requests to `binpick synth`: more parts than the bin can hold, a part too small for the
// physics or wider than the bin, and a huge image are refused at once with one message that
// says what fits; a model of many triangles is simplified for the physics; a bin that fills up
// stops releasing waves and says how many parts it placed; a physics time limit names the
// parts that had not come to rest.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <vector>
#include <chrono>
#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "tests/support/cli_run.hpp"

namespace binpick {
// The sanitized build (./run.sh test --sanitize) runs everything several times slower.
#if defined(__SANITIZE_ADDRESS__)
constexpr double kSanitizerSlowdown = 5;
#else
constexpr double kSanitizerSlowdown = 1;
#endif

namespace {

namespace fs = std::filesystem;

class SynthLimitsCli : public ::testing::Test {
 protected:
  void TearDown() override { fs::remove_all(dir_); }
  // A small image unless `extra` gives the width.
  std::string synth(const std::string& extra) const {
    return fmt::format("synth --out '{}' --cache-dir '{}' --bins 1 {} --no-cloud {}",
                       out_.string(), (dir_ / "cache").string(),
                       extra.find("--width") == std::string::npos ? "--width 64 --height 48" : "",
                       extra);
  }
  // Refused with exit 2 and one line containing `wanted`, before anything was written, in
  // well under the time any physics would take.
  void expect_refused(const std::string& extra, const std::string& wanted) const {
    const auto start = std::chrono::steady_clock::now();
    const auto r = test::run_binpick(synth(extra));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.status, 2) << extra << "\n" << r.err;
    EXPECT_NE(r.err.find("binpick: error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(wanted), std::string::npos) << extra << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(out_ / "test")) << extra;
    // Not a speed claim: a refusal that waited for a decomposition or a drop would take
    // minutes, this is an order of magnitude above a cold start (five times that under ASan).
    EXPECT_LT(seconds, kSanitizerSlowdown * 30.0) << extra;
  }
  int parts_in_bin() const {
    const auto gt = nlohmann::json::parse(test::slurp(out_ / "test" / "000000" / "scene_gt.json"));
    return int(gt.at("0").size());
  }

  const fs::path dir_ = test::fresh_temp_dir("synth_limits");
  const fs::path out_ = dir_ / "data";
};

TEST_F(SynthLimitsCli, MorePartsThanTheBinHoldsAreRefusedWithTheEstimate) {
  // The default bin holds about 3968 bolts (72 l at a packing fraction of 0.5, 9.07 cm^3 each).
  expect_refused("--model builtin:bolt --objects 100000", "the bin holds about 3968");
  expect_refused("--model builtin:bolt --objects 4000 --bin-size 60,60,60", "--bin-size");
}

TEST_F(SynthLimitsCli, PartsTooSmallOrWiderThanTheBinAreRefused) {
  expect_refused("--model builtin:bolt --objects 5 --diameter 0.001", "at least 5 mm");
  expect_refused("--model builtin:bolt --objects 5 --diameter 10000", "more than the bin");
  expect_refused("--model builtin:bolt --objects 5 --distractors builtin:plate --bin-size 100,100,100",
                 "--distractors builtin:plate");
}

TEST_F(SynthLimitsCli, HugeImagesAreRefused) {
  expect_refused("--model builtin:bolt --objects 5 --width 100000", "image size");
}

// A closed UV sphere of `rings` rings and 2 * rings segments, 50 mm across: 4 * rings^2 - 4 *
// rings triangles, as binary STL.
void write_sphere_stl(const fs::path& path, int rings) {
  const int segments = 2 * rings;
  const auto vertex = [&](int ring, int segment) {
    const double theta = M_PI * ring / rings, phi = 2 * M_PI * (segment % segments) / segments;
    return std::array<float, 3>{float(25 * std::sin(theta) * std::cos(phi)),
                                float(25 * std::sin(theta) * std::sin(phi)),
                                float(25 * std::cos(theta))};
  };
  std::vector<std::array<std::array<float, 3>, 3>> triangles;
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      if (i > 0) triangles.push_back({vertex(i, j), vertex(i + 1, j), vertex(i, j + 1)});
      if (i < rings - 1) triangles.push_back({vertex(i, j + 1), vertex(i + 1, j), vertex(i + 1, j + 1)});
    }
  std::ofstream stl(path, std::ios::binary);
  const std::string header(80, '\0');
  stl.write(header.data(), 80);
  const auto count = std::uint32_t(triangles.size());
  stl.write(reinterpret_cast<const char*>(&count), 4);
  const float normal[3] = {0, 0, 0};
  const std::uint16_t attributes = 0;
  for (const auto& t : triangles) {
    stl.write(reinterpret_cast<const char*>(normal), sizeof normal);
    for (const auto& v : t) stl.write(reinterpret_cast<const char*>(v.data()), 12);
    stl.write(reinterpret_cast<const char*>(&attributes), 2);
  }
}

TEST_F(SynthLimitsCli, AModelOfManyTrianglesIsSimplifiedForThePhysicsOnly) {
  // HACD alone would take hours on this (synth/decompose/hacd_simplify.hpp); its hulls come from
  // the mesh simplified to 1000 triangles, and the note says so once.
  const fs::path sphere = dir_ / "sphere.stl";
  write_sphere_stl(sphere, 100);  // 39600 triangles
  const auto r = test::run_binpick(synth(fmt::format("--model '{}' --objects 5", sphere.string())));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string note =
      "39600 triangles; its convex hulls for the physics come from the mesh simplified to 1000";
  const std::size_t at = r.err.find(note);
  EXPECT_NE(at, std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(note, at + 1), std::string::npos) << r.err;
  EXPECT_EQ(parts_in_bin(), 5);
}

TEST_F(SynthLimitsCli, AFullBinStopsReleasingWavesAndSaysHowManyItPlaced) {
  // 26 bolts fit by the estimate (0.48 l at 0.5), but two at a time into a bin 40 mm deep
  // heap over its walls long before.
  const auto r = test::run_binpick(
      synth("--model builtin:bolt --objects 26 --bin-size 120,100,40 --grid 2,1"));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::size_t at = r.err.find("the bin was full after ");
  ASSERT_NE(at, std::string::npos) << r.err;
  const int released = std::stoi(r.err.substr(at + std::string("the bin was full after ").size()));
  EXPECT_LT(released, 26);
  EXPECT_LE(parts_in_bin(), released);
  EXPECT_NE(r.err.find(fmt::format("after {} of 26 parts", released)), std::string::npos) << r.err;
}

TEST_F(SynthLimitsCli, AWallClockLimitNamesThePartsNotAtRest) {
  const auto r = test::run_binpick(
      synth("--model builtin:bolt --objects 6 --max-wall-seconds 0.001"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("NOT at rest (time limit)"), std::string::npos) << r.err;
  // Stopped in the first wave: every part is still falling, and each is named.
  const std::size_t at = r.err.find("parts not at rest (scene_gt indices): ");
  ASSERT_NE(at, std::string::npos) << r.err;
  std::string expected;
  for (int i = 0; i < parts_in_bin(); ++i) expected += (i ? ", " : "") + std::to_string(i);
  const std::string named = "parts not at rest (scene_gt indices): " + expected;
  EXPECT_EQ(r.err.substr(at, named.size()), named);
  EXPECT_EQ(r.err.find_first_of(";\n (", at + named.size()), at + named.size()) << "no more";
}

}  // namespace
}  // namespace binpick
