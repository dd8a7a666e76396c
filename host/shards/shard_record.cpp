#include "host/shards/shard_record.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/core/atomic_file.hpp"
#include "host/core/error.hpp"
#include "host/core/read_file.hpp"
#include "host/shards/shard.hpp"

namespace binpick {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

json to_json(const ShardRecord& r) {
  return {{"verb", r.verb}, {"out", r.out.string()}, {"items", r.items}, {"shards", r.shards}};
}

std::string summary(const ShardRecord& r) {
  return fmt::format("{} of {} in {} shards", r.verb == "synth" ? "bins" : "scenes",
                     describe_ids(r.items), r.shards);
}

}  // namespace

std::optional<ShardRecord> read_shard_record(const fs::path& file) {
  if (!fs::exists(file)) return std::nullopt;
  try {
    const json j = json::parse(read_file_bytes(file));
    ShardRecord r{j.at("verb").get<std::string>(), j.at("out").get<std::string>(),
                  j.at("items").get<std::vector<int>>(), j.at("shards").get<int>()};
    if (r.shards < 1 || r.items.empty()) throw InputError("no items or shards");
    return r;
  } catch (const std::exception& e) {
    throw InputError(fmt::format("{} is not a shard record ({}): remove it and run the shards "
                                 "again",
                                 file.string(), e.what()));
  }
}

void claim_shard_record(const fs::path& file, const ShardRecord& record,
                        const std::function<bool(int item)>& done) {
  const std::optional<ShardRecord> have = read_shard_record(file);
  if (have && *have == record) return;
  if (have && !missing_work(*have, done).items.empty())
    throw InputError(fmt::format(
        "{} belongs to an unfinished sharded batch ({}); this run is {}: give every shard the "
        "same options and the same N, or finish that batch first",
        file.string(), summary(*have), summary(record)));
  write_file_atomically(file, [&](std::ostream& o) { o << to_json(record).dump(1) << "\n"; });
}

MissingWork missing_work(const ShardRecord& record, const std::function<bool(int item)>& done) {
  MissingWork m;
  for (std::size_t p = 0; p < record.items.size(); ++p)
    if (!done(record.items[p])) {
      m.items.push_back(record.items[p]);
      m.shards.push_back(Shard::of(p, record.shards));
    }
  std::sort(m.shards.begin(), m.shards.end());
  m.shards.erase(std::unique(m.shards.begin(), m.shards.end()), m.shards.end());
  return m;
}

std::string describe_ids(const std::vector<int>& ids) {
  std::vector<int> sorted = ids;
  std::sort(sorted.begin(), sorted.end());
  std::string text;
  for (std::size_t i = 0; i < sorted.size();) {
    std::size_t j = i;
    while (j + 1 < sorted.size() && sorted[j + 1] == sorted[j] + 1) ++j;
    if (!text.empty()) text += ", ";
    text += j == i ? fmt::format("{}", sorted[i]) : fmt::format("{}-{}", sorted[i], sorted[j]);
    i = j + 1;
  }
  return text;
}

}  // namespace binpick
