// A flood fill over an image that crosses holes: from seed pixels in 4-neighbour steps, a pixel
// with data joins when joins(last, j) holds, `last` being the last pixel with data on the path to
// it; a missing pixel (missing(j)) is stepped over for up to max_gap pixels in a row. Used where a
// structured-light sensor loses patches of a face (over_rim.cpp: what reaches in over the rim, and
// its faces followed below it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace binpick {

// The pixels with data entered, seeds first, each once. A missing pixel is entered again when a
// path reaches it across a shorter gap. With joins that depend on `last`, steps are taken first in
// first out (breadth first), and a pixel entered across a longer gap first goes on from there with
// its own `last` too. With joins that do not (path_independent), steps are taken fewest missing
// pixels first (pixels with data, then gaps of 1, 2, ...) and a step whose pixel was since reached
// across a shorter gap is dropped: the same pixels, but with three quarters of the pixels missing
// each is entered about once instead of again by every shorter path a breadth-first order finds
// later (docs/decisions/2026-12-07-gap-flood.md).
template <class Missing, class Joins>
std::vector<std::size_t> flood_with_gaps(std::uint32_t width, std::uint32_t height,
                                         const std::vector<std::size_t>& seeds, Missing missing,
                                         Joins joins, std::uint32_t max_gap,
                                         bool path_independent = false) {
  const std::size_t n = std::size_t(width) * height;
  constexpr std::uint32_t unvisited = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> best_gap(n, unvisited);  // 0: a pixel with data entered
  struct Step {
    std::size_t pixel;
    std::size_t last;   // the last pixel with data on the way here
    std::uint32_t gap;  // missing pixels crossed since it
  };
  // queues[g]: the steps onto a pixel g missing pixels past `last` (path_independent; else all in
  // queues[0]), first in first out.
  struct Queue {
    std::vector<Step> steps;
    std::size_t head = 0;
  };
  std::vector<Queue> queues(std::size_t(max_gap) + 1);
  std::vector<std::size_t> entered;
  for (const std::size_t i : seeds)
    if (i < n && best_gap[i] != 0) {
      best_gap[i] = 0;
      queues[0].steps.push_back({i, i, 0});
      entered.push_back(i);
    }
  std::uint32_t gap = 0;  // the queue taken from: the lowest not empty
  while (true) {
    while (gap <= max_gap && queues[gap].head == queues[gap].steps.size()) {
      queues[gap].steps.clear(), queues[gap].head = 0;
      ++gap;
    }
    if (gap > max_gap) break;
    const Step s = queues[gap].steps[queues[gap].head++];
    if (path_independent && best_gap[s.pixel] < s.gap) continue;  // a shorter gap since
    const std::size_t u = s.pixel % width, v = s.pixel / width;
    const std::size_t next[4] = {u > 0 ? s.pixel - 1 : n, u + 1 < width ? s.pixel + 1 : n,
                                 v > 0 ? s.pixel - width : n, v + 1 < height ? s.pixel + width : n};
    for (const std::size_t j : next) {
      if (j == n) continue;
      if (missing(j)) {
        const std::uint32_t g = s.gap + 1;
        if (g > max_gap || g >= best_gap[j]) continue;
        best_gap[j] = g;
        queues[path_independent ? g : 0].steps.push_back({j, s.last, g});
      } else if (best_gap[j] != 0 && joins(s.last, j)) {
        best_gap[j] = 0;
        queues[0].steps.push_back({j, j, 0});
        entered.push_back(j);
        gap = 0;
      }
    }
  }
  return entered;
}

}  // namespace binpick
