#include "host/detect/hypotheses/prerank.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace binpick {

std::vector<std::size_t> prerank_order(const std::vector<double>& votes, std::size_t found) {
  if (votes.size() > found) throw std::logic_error("more coarse votes than highest points");
  std::vector<std::size_t> order(found);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.begin() + std::ptrdiff_t(votes.size()),
                   [&](std::size_t a, std::size_t b) { return votes[a] > votes[b]; });
  return order;
}

}  // namespace binpick
