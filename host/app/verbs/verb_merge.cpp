// `binpick merge PATH`: finishes a sharded batch by hand (normally the shard that finishes last
// does it): detect results (PATH is the --out CSV or its .parts directory) are merged into the
// CSV; a synth dataset (PATH is its directory) is checked to hold every bin. Idempotent, and an
// error naming the missing scenes or bins (and their shards) while any shard's work is missing.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "host/app/verbs/verbs.hpp"
#include "host/core/error.hpp"
#include "host/detect/batch/detect_parts.hpp"
#include "host/shards/shard_record.hpp"
#include "synth/synth_shards.hpp"

namespace binpick::cli {
namespace {

namespace fs = std::filesystem;

// The shard record PATH points at: a dataset's, a results CSV's, or a parts directory's.
ShardRecord record_at(const fs::path& path) {
  std::string text = path.string();
  while (text.size() > 1 && text.back() == '/') text.pop_back();
  for (const fs::path& file : {synth_shard_record_file(text), shard_record_file(text),
                               fs::path(text) / "shards.json"})
    if (auto record = read_shard_record(file)) return *record;
  throw InputError(fmt::format(
      "{}: no sharded batch here (looked for a synth dataset's shards/shards.json and detect "
      "results' .parts/shards.json)",
      path.string()));
}

void run_merge(const std::string& path) {
  const ShardRecord record = record_at(path);
  if (record.verb == "synth") {
    std::cout << check_synth_shards(record) << "\n";
  } else if (record.verb == "detect") {
    const std::size_t rows = merge_detect_parts(record.out, record.items);
    std::cout << fmt::format("merged {} scenes ({} rows); wrote {}\n", record.items.size(), rows,
                             record.out.string());
  } else if (record.verb == "run") {
    throw InputError(fmt::format(
        "{} is a sharded `binpick run`: its report needs the experiment's options, so run the "
        "same command without --shard to finish it (every stage resumes; only what is missing "
        "is done)",
        record.out.string()));
  } else {
    throw InputError(fmt::format("{}: a shard record of '{}', which merge does not know", path,
                                 record.verb));
  }
}

}  // namespace

void add_merge_verb(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  auto* verb = app.add_subcommand(
      "merge",
      "Finish a sharded batch (--shard K/N): merge detect's partial results into its --out CSV, "
      "or check that a synth dataset holds every bin; fails naming what is missing. The shard "
      "that finishes last does this by itself");
  verb->add_option("PATH", *path,
                   "detect's --out CSV (or its .parts directory), or synth's dataset directory")
      ->required();
  verb->callback([path] { run_merge(*path); });
}

}  // namespace binpick::cli
