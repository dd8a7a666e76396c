// The q-quantile of a sample (the element of rank q (n - 1), rounded down; nth_element on a
// copy), for the bin fit's host code. Needs a sample that is not empty.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace binpick {

inline double quantile(std::vector<double> xs, double q) {
  const std::size_t k = std::min(xs.size() - 1, std::size_t(q * double(xs.size() - 1)));
  std::nth_element(xs.begin(), xs.begin() + std::ptrdiff_t(k), xs.end());
  return xs[k];
}

}  // namespace binpick
