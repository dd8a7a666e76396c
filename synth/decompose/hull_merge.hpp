// Merging of convex hulls that HACD left apart although one hull covers them almost as well:
// HACD stops merging clusters where the mesh is concave, even when the concavity is a small
// hole (the built-in bracket: 11 hulls, overlapping to 153 % of the part's volume, for two
// plates with a 7 mm hole each). Contact cost grows with the number of hull pairs, so every
// merge that adds little volume makes the drop cheaper.
#pragma once

#include "synth/decompose/convex_parts.hpp"

namespace binpick {

struct HullMergeOptions {
  // Two hulls merge into the hull of both when that fills at most this fraction of the volume
  // all hulls cover (space inside the merged hull that no hull covered before); cheapest first.
  double max_added_per_merge = 0.01;
  // ... and while all merges together fill at most this fraction: a bound on a long chain of
  // small merges. Of the built-in and the tests' parts only the sheet-metal plate reaches it:
  // closing its three holes fills 3.7 %. At 3 % it kept four slabs, each most of the sheet,
  // overlapping: their side faces inside the sheet push a plate lying on the plate sideways
  // (released 350-plate piles crept: 20 plates over 5 mm/s at any time, against at most 4 as
  // one hull) and the pairs of slabs made each step 2 to 4 times as costly.
  double max_added_total = 0.05;
};

// Greedily merges the pair that adds the least volume until no pair is within the limits.
// Deterministic: volumes are measured on a fixed grid of sample points.
ConvexParts merge_hulls(const ConvexParts& parts, const HullMergeOptions& options);

// The volume covered by the union of the hulls (mm^3, sampled on the same kind of grid).
double union_volume(const ConvexParts& parts);

}  // namespace binpick
