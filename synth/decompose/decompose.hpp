// Approximate convex decomposition of a part with Bullet's HACD, cached on disk.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "host/core/mesh.hpp"
#include "synth/decompose/convex_parts.hpp"
#include "synth/decompose/hull_merge.hpp"

namespace binpick {

// HACD's knobs. The part is normalised to a unit bounding-box diagonal before HACD sees it, so
// these values mean the same thing for a 5 mm and a 500 mm part.
struct DecomposeOptions {
  double concavity = 100.0;       // max concavity, in HACD's internal units (diagonal 2000)
  double compacity_weight = 0.1;  // HACD's alpha: prefers compact clusters
  double volume_weight = 0.0;     // HACD's beta
  std::size_t min_clusters = 2;   // HACD stops merging at this many hulls
  // At most this many hulls after the merging below (0 = no limit): a part that still has more is
  // decomposed again without the concavity limit, down to this many, and merged again. Contact
  // cost grows with the pairs of hulls that touch: the built-in tee's 15 hulls (long slivers
  // around its bore, whose boxes overlap the neighbours' in every orientation) made its
  // 350-part drop ten times as costly per moving part as the bracket's 2, about two minutes;
  // at 8 it takes about half as long. Its 8 hulls fill about half of the bore (the 15 a fifth),
  // where another tee's wall could reach only at a rim, and stand out of the part's outline
  // as far as the 15. 8 keeps the tests' torus as it is: capping it at 6 coarsened its hulls
  // beyond the span and stability tests. The other built-in parts have 1 to 4.
  std::size_t max_hulls = 8;
  // Then hulls that one hull covers almost as well are merged (hull_merge.hpp): the built-in
  // bracket's 11 become its two plates, holes filled (1.6 % of its volume), and its 350-part
  // drop takes a sixth of the time; the torus, whose first merge would fill 2.3 %, keeps 8.
  // max_added_per_merge = 0 turns merging off.
  HullMergeOptions merge;
  // Finally every hull grows until no mesh vertex lies farther outside all of them than this
  // fraction of the part's bounding-box diagonal (hull_cover.hpp); 0 = keep HACD's hulls.
  double max_uncovered = 0.01;
  // HACD's hulls have at most this many vertices (max_uncovered then adds some where the mesh
  // sticks out: the torus's 8 hulls go from 12 to 22 on average). Collision tests walk every
  // vertex: 12 kept a 350-part torus bin twice as fast as 32.
  std::size_t max_hull_vertices = 12;
  // HACD sees at most max_hacd_triangles (hacd_simplify.hpp; every built-in part has fewer, so
  // their hulls are HACD's on the mesh itself): a mesh of more is simplified to
  // hacd_target_triangles first.
  std::size_t max_hacd_triangles = 1500;
  std::size_t hacd_target_triangles = 1000;
  bool add_extra_dist_points = true;  // needed to see the concavity of holes (a torus)
  bool add_neighbours_dist_points = false;
  bool add_faces_points = true;
  // Empty: $BINPICK_CACHE_DIR, else $XDG_CACHE_HOME/binpick, else ~/.cache/binpick.
  std::filesystem::path cache_dir;
  bool use_cache = true;
};

// The hulls of `part` (mm, part frame); served from the cache when the same mesh was
// decomposed with the same options before. Throws InputError for an empty or invalid mesh.
ConvexParts decompose_convex(const Mesh& part, const DecomposeOptions& options);

// The same without the cache: always runs HACD.
ConvexParts decompose_convex_uncached(const Mesh& part, const DecomposeOptions& options);

}  // namespace binpick
