// Random numbers for the drop, from std::mt19937_64's raw bits only: the standard library's
// distributions differ between implementations, and the same seed must give the same bin
// everywhere.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

namespace binpick {

// Uniform in [0, 1): the top 53 bits as a double's mantissa.
inline double uniform_unit(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

// Uniform on SO(3) (Shoemake, "Uniform random rotations", Graphics Gems III).
inline Eigen::Quaterniond uniform_rotation(std::mt19937_64& rng) {
  const double u1 = uniform_unit(rng), u2 = uniform_unit(rng), u3 = uniform_unit(rng);
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const double t2 = 2.0 * std::numbers::pi * u2, t3 = 2.0 * std::numbers::pi * u3;
  return Eigen::Quaterniond(b * std::cos(t3), a * std::sin(t2), a * std::cos(t2), b * std::sin(t3));
}

}  // namespace binpick
