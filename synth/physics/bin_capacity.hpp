// How many parts a bin can hold, estimated before any physics from the parts' volumes, so that
// `synth --objects 100000` into the default bin is refused at once instead of dropping wave
// after wave above a full bin.
//
// The estimate: the bin's interior volume (W * D * H, filled to the top of the walls) times the
// packing fraction of a random pile, over the mean volume of the parts released (each kind's
// closed-mesh volume, weighted by its count). The packing fraction of a random pile of rigid
// non-convex parts is well below that of spheres (random close packing 0.64, random loose
// 0.55): interlocking arms, heads and flanges hold each other apart.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "host/core/mesh.hpp"

namespace binpick {

// Measured: 165 bolts (this estimate for a 200 x 150 x 100 bin) dropped 6 at a time left 157
// in the bin, heaped to the top of the walls: 0.47 of the interior, the heap included. Taken
// as the upper end, so that only a bin that even a dense pile could not hold is refused;
// looser piles stop when full instead (drop.hpp, DropStats::full).
inline constexpr double kRandomPilePacking = 0.5;

struct BinCapacity {
  double bin_volume_mm3 = 0;   // interior, up to the top of the walls
  double part_volume_mm3 = 0;  // mean over the parts released
  double packing_fraction = kRandomPilePacking;
  int parts = 0;               // floor(bin * packing / part)
};

// `meshes[k]` closed, mm; `counts[k]` parts of it. Throws InputError if a mesh encloses no
// volume.
BinCapacity estimate_bin_capacity(const Eigen::Vector3d& bin_size_mm,
                                  const std::vector<const Mesh*>& meshes,
                                  const std::vector<int>& counts);

// Bullet inflates every convex hull by a collision margin of 0.04 of its units (0.4 mm,
// synth/physics/part_shape.cpp): a part under this diameter would be mostly margin, and pile
// like pebbles rather than like itself.
inline constexpr double kMinPartDiameterMm = 5.0;

// Throws InputError, naming `what` (e.g. "--model builtin:bolt"), for a part under
// kMinPartDiameterMm or one whose diameter exceeds the bin interior's width or depth (no drop
// position would hold it), saying how to rescale it or enlarge the bin.
void check_part_size(const std::string& what, double diameter_mm, const Eigen::Vector3d& bin_size_mm);

// Throws InputError when `objects` exceeds capacity.parts, saying the estimate, how it was made
// and how to get a bigger bin.
void check_bin_capacity(int objects, const BinCapacity& capacity);

}  // namespace binpick
