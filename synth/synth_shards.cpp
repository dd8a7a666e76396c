#include "synth/synth_shards.hpp"

#include <fmt/format.h>

#include "host/core/error.hpp"

namespace binpick {
namespace fs = std::filesystem;

fs::path synth_state_dir(const fs::path& dataset) { return dataset / "shards"; }

fs::path synth_shard_record_file(const fs::path& dataset) {
  return synth_state_dir(dataset) / "shards.json";
}

bool bin_done(const fs::path& dataset, int bin) {
  return fs::exists(dataset / "test" / fmt::format("{:06d}", bin) / "scene_gt.json");
}

ShardRecord synth_shard_record(const fs::path& dataset, int bins, int shards) {
  ShardRecord r{"synth", fs::absolute(dataset), {}, shards};
  for (int b = 0; b < bins; ++b) r.items.push_back(b);
  return r;
}

std::string check_synth_shards(const ShardRecord& record) {
  const MissingWork m = missing_work(record, [&](int b) { return bin_done(record.out, b); });
  if (!m.items.empty()) {
    std::string shards;
    for (int s : m.shards) shards += fmt::format("{}{}/{}", shards.empty() ? "" : ", ", s + 1, record.shards);
    throw InputError(fmt::format("{}: bins {} are missing (shards {})", record.out.string(),
                                 describe_ids(m.items), shards));
  }
  return fmt::format("{}: all {} bins present", record.out.string(), record.items.size());
}

}  // namespace binpick
