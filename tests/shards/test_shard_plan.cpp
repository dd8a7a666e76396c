// The pieces of sharding without a process: --shard K/N parsing, the round-robin split (every
// item in exactly one shard, for any N), the shard record (claimed, kept, refused while another
// batch is unfinished), the missing work and its shards, and the id ranges of messages.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "host/core/error.hpp"
#include "host/shards/shard.hpp"
#include "host/shards/shard_record.hpp"
#include "tests/support/cli_run.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;

TEST(Shard, ParsesKOfNAndRefusesTheRest) {
  const Shard s = parse_shard("2/4");
  EXPECT_EQ(s.index, 1);
  EXPECT_EQ(s.count, 4);
  EXPECT_EQ(s.name(), "2/4");
  EXPECT_TRUE(s.sharded());
  EXPECT_FALSE(parse_shard("").sharded());
  EXPECT_FALSE(parse_shard("1/1").sharded());
  for (const char* bad : {"0/4", "5/4", "4", "/4", "2/", "a/b", "2/4x", "-1/4", "1/0", "1/100001",
                          " 1/2", "1//2"})
    EXPECT_THROW(parse_shard(bad), InputError) << bad;
}

TEST(Shard, EveryItemBelongsToExactlyOneShard) {
  for (int n = 1; n <= 7; ++n) {
    std::multiset<std::size_t> seen;
    for (int k = 0; k < n; ++k) {
      const Shard s{k, n};
      std::size_t own = 0;
      for (std::size_t p = 0; p < 23; ++p)
        if (s.owns(p)) {
          seen.insert(p);
          ++own;
          EXPECT_EQ(Shard::of(p, n), k);
        }
      // Round robin: shares differ by at most one item.
      EXPECT_GE(own, 23u / n);
      EXPECT_LE(own, 23u / n + 1);
    }
    EXPECT_EQ(seen.size(), 23u);
    for (std::size_t p = 0; p < 23; ++p) EXPECT_EQ(seen.count(p), 1u) << n << " " << p;
  }
}

TEST(ShardRecord, MissingWorkNamesItemsAndShards) {
  const ShardRecord r{"detect", "/x/out.csv", {10, 11, 12, 13, 14}, 2};
  const std::set<int> have{10, 12, 13};
  const MissingWork m = missing_work(r, [&](int id) { return have.count(id) > 0; });
  EXPECT_EQ(m.items, (std::vector<int>{11, 14}));
  EXPECT_EQ(m.shards, (std::vector<int>{0, 1}));  // positions 1 and 4
  EXPECT_TRUE(missing_work(r, [](int) { return true; }).items.empty());
  EXPECT_EQ(describe_ids({7, 1, 2, 3, 5}), "1-3, 5, 7");
}

TEST(ShardRecord, IsClaimedKeptAndRefusedWhileAnotherBatchIsUnfinished) {
  const fs::path dir = test::fresh_temp_dir("shard_record");
  const fs::path file = dir / "shards.json";
  const ShardRecord a{"detect", dir / "a.csv", {0, 1, 2}, 2};
  std::set<int> done;
  const auto is_done = [&](int id) { return done.count(id) > 0; };
  EXPECT_FALSE(read_shard_record(file));
  claim_shard_record(file, a, is_done);
  ASSERT_TRUE(read_shard_record(file));
  EXPECT_EQ(*read_shard_record(file), a);
  claim_shard_record(file, a, is_done);  // the same batch: kept

  ShardRecord b = a;
  b.shards = 3;  // another N while a's scenes are missing
  EXPECT_THROW(claim_shard_record(file, b, is_done), InputError);
  b = a;
  b.items = {0, 1};
  EXPECT_THROW(claim_shard_record(file, b, is_done), InputError);
  done = {0, 1, 2};  // a finished: a new batch may take over
  claim_shard_record(file, b, is_done);
  EXPECT_EQ(*read_shard_record(file), b);

  std::ofstream(file) << "{\"verb\": 3}";
  EXPECT_THROW(read_shard_record(file), InputError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace binpick
