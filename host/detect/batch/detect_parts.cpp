#include "host/detect/batch/detect_parts.hpp"

#include <fmt/format.h>

#include "host/core/atomic_file.hpp"
#include "host/core/error.hpp"
#include "host/core/read_file.hpp"
#include "host/detect/batch/detect_batch.hpp"
#include "host/detect/batch/picks_csv.hpp"
#include "host/formats/bop/results_csv.hpp"
#include "host/shards/shard_record.hpp"

namespace binpick {
namespace fs = std::filesystem;

fs::path parts_dir(const fs::path& out) { return fs::path(out.string() + ".parts"); }

fs::path part_file(const fs::path& out, int scene) {
  return parts_dir(out) / fmt::format("scene_{:06d}.csv", scene);
}

fs::path details_part_file(const fs::path& out, int scene) {
  return parts_dir(out) / fmt::format("scene_{:06d}.details.csv", scene);
}

fs::path picks_part_file(const fs::path& out, int scene) {
  return parts_dir(out) / fmt::format("scene_{:06d}.picks.csv", scene);
}

fs::path shard_record_file(const fs::path& out) { return parts_dir(out) / "shards.json"; }

namespace {

fs::path details_header_file(const fs::path& out) { return parts_dir(out) / "details_header.csv"; }
fs::path picks_marker_file(const fs::path& out) { return parts_dir(out) / "picks_header.csv"; }

}  // namespace

void write_details_header(const fs::path& out, const std::string& header) {
  const fs::path file = details_header_file(out);
  // The one-model header is the default: no file, as parts made before several models were.
  std::error_code ec;
  if (header == details_header(false)) fs::remove(file, ec);
  else write_file_atomically(file, [&](std::ostream& s) { s << header; });
}

void write_picks_marker(const fs::path& out, bool picks) {
  const fs::path file = picks_marker_file(out);
  std::error_code ec;
  if (!picks) fs::remove(file, ec);
  else write_file_atomically(file, [&](std::ostream& s) { s << kPicksCsvHeader; });
}

void prepare_parts(const fs::path& out, const std::string& fingerprint) {
  const fs::path dir = parts_dir(out);
  const fs::path stamp = dir / "fingerprint.json";
  std::error_code ec;
  if (fs::is_directory(dir) && fs::is_regular_file(stamp) && read_file_bytes(stamp) == fingerprint)
    return;
  if (fs::exists(dir)) {
    for (const auto& entry : fs::directory_iterator(dir)) {
      const std::string name = entry.path().filename().string();
      if (name.starts_with("scene_") && name.ends_with(".csv")) fs::remove(entry.path(), ec);
    }
    fs::remove(shard_record_file(out), ec);
  }
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir)) throw InputError("cannot create " + dir.string());
  write_file_atomically(stamp, [&](std::ostream& s) { s << fingerprint; });
}

bool scene_done(const fs::path& out, int scene) { return fs::is_regular_file(part_file(out, scene)); }

std::size_t merge_detect_parts(const fs::path& out, const std::vector<int>& scenes) {
  std::vector<int> missing;
  for (int scene : scenes)
    if (!scene_done(out, scene)) missing.push_back(scene);
  if (!missing.empty())
    throw InputError(fmt::format("{}: scenes {} are not done yet", parts_dir(out).string(),
                                 describe_ids(missing)));
  std::vector<bop::ResultRow> all;
  for (int scene : scenes) {
    const auto rows = bop::read_results_csv(part_file(out, scene));
    all.insert(all.end(), rows.begin(), rows.end());
  }
  const fs::path header = details_header_file(out);
  std::string details = fs::is_regular_file(header) ? read_file_bytes(header) : details_header(false);
  for (int scene : scenes) details += read_file_bytes(details_part_file(out, scene));
  write_file_atomically(details_path(out), [&](std::ostream& o) { o << details; });
  if (fs::is_regular_file(picks_marker_file(out))) {
    std::string picks = kPicksCsvHeader;
    for (int scene : scenes) picks += read_file_bytes(picks_part_file(out, scene));
    write_file_atomically(picks_path(out), [&](std::ostream& o) { o << picks; });
  }
  bop::write_results_csv(out, all);
  return all.size();
}

}  // namespace binpick
