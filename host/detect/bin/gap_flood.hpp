// A flood fill over an image that crosses holes: from seed pixels in 4-neighbour steps, a pixel
// with data joins when joins(last, j) holds, `last` being the last pixel with data on the path
// to it; a missing pixel (missing(j)) is stepped over for up to max_gap pixels in a row. Used
// where a structured-light sensor loses patches of a face (over_rim.cpp: what reaches in over
// the rim, and its faces followed below it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace binpick {

// The pixels with data entered, seeds first, each once. A missing pixel is entered again when a
// path reaches it across a shorter gap, so the result does not depend on which path came first.
template <class Missing, class Joins>
std::vector<std::size_t> flood_with_gaps(std::uint32_t width, std::uint32_t height,
                                         const std::vector<std::size_t>& seeds, Missing missing,
                                         Joins joins, std::uint32_t max_gap) {
  const std::size_t n = std::size_t(width) * height;
  constexpr std::uint32_t unvisited = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> best_gap(n, unvisited);  // 0: a pixel with data entered
  struct Step {
    std::size_t pixel;
    std::size_t last;   // the last pixel with data on the way here
    std::uint32_t gap;  // missing pixels crossed since it
  };
  std::vector<Step> queue;
  std::vector<std::size_t> entered;
  for (const std::size_t i : seeds)
    if (i < n && best_gap[i] != 0) {
      best_gap[i] = 0;
      queue.push_back({i, i, 0});
      entered.push_back(i);
    }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const Step s = queue[head];
    const std::size_t u = s.pixel % width, v = s.pixel / width;
    const std::size_t next[4] = {u > 0 ? s.pixel - 1 : n, u + 1 < width ? s.pixel + 1 : n,
                                 v > 0 ? s.pixel - width : n, v + 1 < height ? s.pixel + width : n};
    for (const std::size_t j : next) {
      if (j == n) continue;
      if (missing(j)) {
        const std::uint32_t gap = s.gap + 1;
        if (gap > max_gap || gap >= best_gap[j]) continue;
        best_gap[j] = gap;
        queue.push_back({j, s.last, gap});
      } else if (best_gap[j] != 0 && joins(s.last, j)) {
        best_gap[j] = 0;
        queue.push_back({j, j, 0});
        entered.push_back(j);
      }
    }
  }
  return entered;
}

}  // namespace binpick
