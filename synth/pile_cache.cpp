#include "synth/pile_cache.hpp"

namespace binpick {

const DropResult* PileCache::find(const std::string& key, int bin) const {
  if (key != key_) return nullptr;
  const auto it = piles_.find(bin);
  return it == piles_.end() ? nullptr : &it->second;
}

void PileCache::store(const std::string& key, int bin, const DropResult& pile) {
  if (key != key_) {
    piles_.clear();
    key_ = key;
  }
  piles_[bin] = pile;
}

}  // namespace binpick
