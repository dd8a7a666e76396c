// The OpenCL runtime on the real PoCL device: device choice, embedded programs, build errors,
// and the depth_to_points kernel against its C++ reference.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "host/runtime/cl/cl_buffer.hpp"
#include "host/core/error.hpp"
#include "host/detect/scene/depth_to_points.hpp"
#include "tests/support/test_device.hpp"

using namespace binpick;
using binpick::test::test_device;

TEST(ClRuntime, ChoosesAPoclCpuDevice) {
  auto devices = ocl::list_devices();
  ASSERT_FALSE(devices.empty());
  int chosen = 0;
  for (const auto& d : devices) chosen += d.chosen;
  EXPECT_EQ(chosen, 1);
  EXPECT_NE(ocl::Device::shared().description().find("Portable Computing Language"),
            std::string::npos);
}

TEST(ClRuntime, IncludesOfEmbeddedHeadersAreInlined) {
  const std::string src = ocl::resolved_source("depth_to_points.cl");
  EXPECT_NE(src.find("BINPICK_SHARED_H"), std::string::npos);
  EXPECT_EQ(src.find("#include \"binpick_shared.h\""), std::string::npos);
}

TEST(ClRuntime, FailedBuildCarriesTheCompilerLog) {
  try {
    ocl::Device::shared().build("broken.cl", "__kernel void f(__global float* x) { x[0] = y; }");
    FAIL() << "a broken kernel built";
  } catch (const DeviceError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("broken.cl"), std::string::npos) << msg;
    EXPECT_NE(msg.find("undeclared identifier"), std::string::npos) << msg;
  }
}

TEST(ClRuntime, UnknownProgramAndKernelAreClearErrors) {
  EXPECT_THROW(ocl::Device::shared().kernel("no_such_file.cl", "k"), DeviceError);
  EXPECT_THROW(ocl::Device::shared().kernel("depth_to_points.cl", "no_such_kernel"), DeviceError);
}

TEST(ClRuntime, EmptyBuffersAndLaunchesAreAllowed) {
  auto& dev = ocl::Device::shared();
  ocl::Buffer<float> empty(dev, 0);
  EXPECT_TRUE(empty.read(dev).empty());
}

namespace {

bp_camera random_camera(std::mt19937& rng, std::uint32_t w, std::uint32_t h) {
  std::uniform_real_distribution<float> f(300.0f, 2000.0f), c(-10.0f, 10.0f), s(0.05f, 1.0f);
  return {f(rng), f(rng), w / 2.0f + c(rng), h / 2.0f + c(rng), s(rng), w, h, 0};
}

}  // namespace

TEST(DepthToPoints, MatchesReferenceOnRandomImages) {
  std::mt19937 rng(7);
  for (auto [w, h] : {std::pair{1u, 1u}, {37u, 11u}, {160u, 90u}}) {
    bp_camera cam = random_camera(rng, w, h);
    DepthImage depth{w, h, std::vector<std::uint16_t>(std::size_t(w) * h)};
    std::uniform_int_distribution<int> raw(0, 65535), zero(0, 4);
    for (auto& d : depth.raw) d = zero(rng) == 0 ? 0 : std::uint16_t(raw(rng));
    const PointImage got = depth_to_points(test_device(), depth, cam);
    const PointImage want = depth_to_points_reference(depth, cam);
    ASSERT_EQ(got.xyzw.size(), want.xyzw.size());
    for (std::size_t i = 0; i < got.xyzw.size(); ++i)
      // Same float operations in the same order: the only freedom is fused multiply-add.
      ASSERT_NEAR(got.xyzw[i], want.xyzw[i], 1e-5f * (1.0f + std::fabs(want.xyzw[i]))) << i;
  }
}

TEST(DepthToPoints, AllZeroImageGivesNoPoints) {
  std::mt19937 rng(3);
  bp_camera cam = random_camera(rng, 8, 8);
  DepthImage depth{8, 8, std::vector<std::uint16_t>(64, 0)};
  for (float v : depth_to_points(test_device(), depth, cam).xyzw) EXPECT_EQ(v, 0.0f);
}

TEST(DepthToPoints, MismatchedSizeAndBadCameraAreInputErrors) {
  std::mt19937 rng(5);
  bp_camera cam = random_camera(rng, 8, 8);
  DepthImage wrong{4, 4, std::vector<std::uint16_t>(16, 1)};
  EXPECT_THROW(depth_to_points(test_device(), wrong, cam), InputError);
  DepthImage ok{8, 8, std::vector<std::uint16_t>(64, 1)};
  cam.fx = 0;
  EXPECT_THROW(depth_to_points(test_device(), ok, cam), InputError);
  cam.fx = NAN;
  EXPECT_THROW(depth_to_points(test_device(), ok, cam), InputError);
}

// Programs are built once per device: prebuild pays for the build and says how long it took;
// asking again costs nothing.
TEST(ClRuntime, PrebuildBuildsEachProgramOnce) {
  ocl::Device dev;  // a device of its own: nothing is built in it yet
  EXPECT_GT(dev.prebuild({"scene_lowpass.cl", "depth_to_points.cl"}), 0.0);
  EXPECT_EQ(dev.prebuild({"depth_to_points.cl", "scene_lowpass.cl"}), 0.0);
  EXPECT_EQ(dev.prebuild({}), 0.0);
  EXPECT_THROW(dev.prebuild({"no_such_program.cl"}), DeviceError);
}
