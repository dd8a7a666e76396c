// `--shard K/N`: one of N processes doing a deterministic share of a batch's work items (the
// scenes of `detect`, the bins of `synth`). Items are dealt round robin by their position in
// the batch's ordered list, so shards get equal shares and any N gives the same items overall.
#pragma once

#include <cstddef>
#include <string>

namespace binpick {

struct Shard {
  int index = 0;  // 0-based: --shard K/N has index K - 1
  int count = 1;  // 1: the whole batch in one process

  bool sharded() const { return count > 1; }
  // Whether the item at `position` of the batch's list is this shard's.
  bool owns(std::size_t position) const { return int(position % std::size_t(count)) == index; }
  // The shard (0-based) that owns the item at `position` among `count` shards.
  static int of(std::size_t position, int count) { return int(position % std::size_t(count)); }
  std::string name() const;  // "K/N"
};

// Parses "K/N" with 1 <= K <= N <= 100000; "" is the whole batch. InputError naming --shard
// for anything else.
Shard parse_shard(const std::string& text);

}  // namespace binpick
