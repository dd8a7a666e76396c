// Detection refuses a depth image too large for the machine up front (host/detect/
// image_memory.hpp): the estimate grows with the pixels, the message names the size and both
// amounts, and the paper's and a large industrial sensor's images fit on this kind of machine.
#include <gtest/gtest.h>

#include <string>

#include "host/core/error.hpp"
#include "host/detect/scene/image_memory.hpp"

using namespace binpick;

TEST(ImageMemory, EstimateCoversTheMeasuredPeaks) {
  // Measured peaks (resident set of `binpick detect`): 202 MB at 1600 x 900, 300 MB at 2064 x 1544.
  EXPECT_GE(detect_memory_estimate(1600, 900), 202ull << 20);
  EXPECT_GE(detect_memory_estimate(2064, 1544), 300ull << 20);
  EXPECT_LT(detect_memory_estimate(2064, 1544), 600ull << 20);  // not wildly pessimistic
  EXPECT_GT(detect_memory_estimate(4000, 3000), detect_memory_estimate(2064, 1544));
}

TEST(ImageMemory, TooLargeAnImageIsOneClearError) {
  const std::uint64_t eight_gib = 8ull << 30;
  EXPECT_NO_THROW(check_image_fits_in_memory(2064, 1544, eight_gib));
  try {
    check_image_fits_in_memory(20000, 20000, eight_gib);
    FAIL() << "a 400-megapixel image fits in 8 GiB?";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("20000 x 20000 pixels (400 megapixels)"), std::string::npos) << m;
    EXPECT_NE(m.find("about 24.0 GiB"), std::string::npos) << m;
    EXPECT_NE(m.find("this machine's 8.0 GiB"), std::string::npos) << m;
  }
  EXPECT_NO_THROW(check_image_fits_in_memory(1ull << 20, 1ull << 20, 0));  // unknown: no check
  EXPECT_GT(physical_memory_bytes(), 0u);
}
