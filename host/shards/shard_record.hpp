// shards.json: what a sharded batch is made of, written by its shards next to their partial
// outputs so that whoever merges (the shard that finishes last, or `binpick merge`) knows the
// whole batch: the verb, its output, the ordered item ids and the number of shards.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace binpick {

struct ShardRecord {
  std::string verb;                 // "detect", "synth"
  std::filesystem::path out;        // absolute: the merged output (a file or a dataset)
  std::vector<int> items;           // scene ids or bin numbers, in batch order
  int shards = 1;                   // N of --shard K/N

  bool operator==(const ShardRecord&) const = default;
};

// Reads FILE; nullopt if it does not exist, InputError if it is not a record.
std::optional<ShardRecord> read_shard_record(const std::filesystem::path& file);

// Writes the record to FILE unless the same one is there. A different record is replaced only
// when every one of its items is done (its batch finished): a shard of another batch must not
// mix into an unfinished one, so that is an InputError naming both.
void claim_shard_record(const std::filesystem::path& file, const ShardRecord& record,
                        const std::function<bool(int item)>& done);

// The items of `record` that are not done, and the shards (0-based) they belong to.
struct MissingWork {
  std::vector<int> items;
  std::vector<int> shards;  // ascending, unique
};
MissingWork missing_work(const ShardRecord& record, const std::function<bool(int item)>& done);

// "3, 5-9, 12": ids (ascending) as ranges, for messages.
std::string describe_ids(const std::vector<int>& ids);

}  // namespace binpick
