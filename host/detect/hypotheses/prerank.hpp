// The order the highest points are voted in (beyond the paper; docs/detect/hypotheses.md,
// "Ranked by a coarse vote"). The paper votes on the few highest points; in a cell with other
// parts and clutter the highest are often not the part sought, and more of them cost a full
// vote, refinement and verification each. So the first `--prerank` highest points are each
// voted on at a few reference points first, and taken in order of their best pose's votes per
// reference point: a crop on the part sought gathers many votes for one pose, one on anything
// else few. Per reference point, as a larger crop has more of them (a larger part beside a
// small one sought).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "host/core/mesh.hpp"

namespace binpick {

// The coarse vote's reference points at least (all points in a smaller crop): a few, as the
// paper's 2 % of a small part's crop, vary too much.
inline constexpr double kPrerankRefs = 10;

// A highest point's neighbourhood, as voted on: sampled once, shared by the coarse ranking and
// the vote.
struct HypothesisCrop {
  PointCloud cloud;         // subsampled at the model's voxel, with normals
  std::size_t cropped = 0;  // points inside the sphere before subsampling
  std::string reason;       // why it is not voted on; empty: it is
  bool flat = false;        // the reason is the flat-region test (the next point stands in)
};

// The highest points' order: the first `ranked` of `found` by votes, most first (ties: height
// order), those not voted on (votes < 0) after them; the rest in height order. votes[k] is the
// coarse vote of highest point k < ranked.
std::vector<std::size_t> prerank_order(const std::vector<double>& votes, std::size_t found);

}  // namespace binpick
