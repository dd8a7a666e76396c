// The Vulkan runtime on the real lavapipe device, with validation on: device choice and the
// zbuffer_to_points compute shader against its C++ reference.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>

#include "host/core/error.hpp"
#include "synth/render/zbuffer_to_points.hpp"
#include "host/runtime/vk/vk_compute.hpp"

using namespace binpick;

namespace {
// Every Vulkan call in this suite runs under the validation layer; an error fails the test.
const bool validation_on = [] { return setenv("BINPICK_VK_VALIDATION", "1", 1) == 0; }();
}  // namespace

TEST(VkRuntime, ChoosesLavapipeWithValidation) {
  ASSERT_TRUE(validation_on);
  auto devices = vkrt::list_devices();
  ASSERT_FALSE(devices.empty());
  auto& ctx = vkrt::Context::shared();
  EXPECT_TRUE(ctx.validation_enabled());
  EXPECT_NE(ctx.description().find("llvmpipe"), std::string::npos) << ctx.description();
}

TEST(VkRuntime, UnknownShaderIsAClearError) {
  EXPECT_THROW(vkrt::ComputeProgram(vkrt::Context::shared(), "no_such.comp", 1, 0), DeviceError);
}

TEST(ZBufferToPoints, MatchesReferenceOnRandomZBuffers) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> b01(0.0f, 1.0f), f(500.0f, 2000.0f);
  for (auto [w, h] : {std::pair{1u, 1u}, {17u, 33u}, {160u, 90u}}) {
    ZBufferCamera cam{w, h, f(rng), f(rng), w / 2.0f, h / 2.0f, 500.0f, 1100.0f};
    std::vector<float> z(std::size_t(w) * h);
    for (auto& v : z) v = b01(rng);
    z[0] = 1.0f;  // the far plane: no surface
    const auto got = zbuffer_to_points(z, cam);
    const auto want = zbuffer_to_points_reference(z, cam);
    ASSERT_EQ(got.size(), want.size());
    // Tolerance: a few float ulps of the mm values (division and FMA may round differently).
    for (std::size_t i = 0; i < got.size(); ++i)
      ASSERT_NEAR(got[i], want[i], 2e-6f * (1.0f + std::fabs(want[i]))) << i;
    EXPECT_EQ(got[3], 0.0f);
  }
}

TEST(ZBufferToPoints, NearAndFarPlanesGiveTheirDistances) {
  ZBufferCamera cam{2, 1, 1000.0f, 1000.0f, 0.0f, 0.0f, 400.0f, 1200.0f};
  const auto p = zbuffer_to_points({0.0f, 0.999999f}, cam);
  EXPECT_NEAR(p[2], 400.0f, 1e-3f);
  EXPECT_NEAR(p[6], 1200.0f, 1.0f);
}

TEST(ZBufferToPoints, DegenerateInputs) {
  ZBufferCamera cam{2, 2, 1000.0f, 1000.0f, 1.0f, 1.0f, 400.0f, 1200.0f};
  const auto p = zbuffer_to_points({NAN, -1.0f, 2.0f, 1.0f}, cam);
  for (float v : p) EXPECT_EQ(v, 0.0f);
  EXPECT_THROW(zbuffer_to_points({0.5f}, cam), InputError);
  cam.far_mm = cam.near_mm;
  EXPECT_THROW(zbuffer_to_points({0, 0, 0, 0}, cam), InputError);
}

TEST(VkRuntime, ValidationErrorsBecomeDeviceErrors) {
  auto& ctx = vkrt::Context::shared();
  ASSERT_TRUE(ctx.validation_enabled());
  // A zero-sized buffer breaks VUID-VkBufferCreateInfo-size-00912: the layer must say so.
  VkBufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  info.size = 0;
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  VkBuffer buffer = VK_NULL_HANDLE;
  vkCreateBuffer(*ctx.device(), &info, nullptr, &buffer);
  if (buffer != VK_NULL_HANDLE) vkDestroyBuffer(*ctx.device(), buffer, nullptr);
  EXPECT_THROW(ctx.check_validation("creating an empty buffer"), DeviceError);
  EXPECT_NO_THROW(ctx.check_validation("nothing"));  // the messages were consumed
}
