// Per-part sleeping for a pile. Bullet puts bodies to sleep by islands of touching bodies and
// wakes a whole island when one of its bodies is hit; a pile on the bin floor is one island,
// so every landing wave re-simulated the entire pile until all of it slept again: most of a
// bin's time (docs/synthesis.md). Here a part at rest whose neighbours are at rest too is made
// static (static bodies do not join islands), and a part hitting the pile makes the frozen
// parts it hits dynamic again, and the frozen parts that touch those: they carry the hit part
// and may have to give way under it. A wake-up spreads further only as far as parts are
// pushed.
//
// Touching, not within a part diameter of the hit part: a pile shallower than a part is wide
// lies within a diameter of the whole landing wave, which then woke all of it. Not only the
// parts hit: the piles then sag more when released
// (docs/decisions/2026-11-24-pile-freezer-touching.md).
#pragma once

#include "synth/physics/bin_world.hpp"

namespace binpick {

struct FreezeCounts {
  int frozen = 0;
  int thawed = 0;
};

// One pass over the contacts of the world; call it every few steps.
FreezeCounts update_frozen_parts(BinWorld& world);

}  // namespace binpick
