// Piles already simulated in this process. `binpick run` renders the same bins at several noise
// levels, and a bin's pile depends on the seed, the parts and the drop, not on the noise or the
// sensor: without the cache it simulated every pile once per level, and the physics is most of a
// bin's time (a 350-part bin: about a minute of physics, two seconds of rendering). Physics is
// deterministic, so a pile taken from the cache is the pile a new simulation would give, and the
// datasets are byte for byte those made without it.
#pragma once

#include <map>
#include <string>

#include "synth/physics/drop.hpp"

namespace binpick {

class PileCache {
 public:
  // The pile of `bin` simulated with the physics inputs `key` (physics_key), or nullptr.
  const DropResult* find(const std::string& key, int bin) const;
  // Keeps the pile; a different key than the stored piles' drops them first.
  void store(const std::string& key, int bin, const DropResult& pile);

 private:
  std::string key_;
  std::map<int, DropResult> piles_;
};

}  // namespace binpick
