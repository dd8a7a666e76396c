// The partial outputs of a detection batch (detect_batch.hpp): OUT.parts/ holds one results part
// and one details part per finished scene, the fingerprint of the run they belong to and, when
// the batch is sharded, shards.json. Merging concatenates the parts in scene order into OUT and
// its details file; it reads only the parts, so it gives the same bytes whichever process (or
// shard) ran which scene.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace binpick {

std::filesystem::path parts_dir(const std::filesystem::path& out);  // OUT.parts
std::filesystem::path part_file(const std::filesystem::path& out, int scene);
std::filesystem::path details_part_file(const std::filesystem::path& out, int scene);
std::filesystem::path picks_part_file(const std::filesystem::path& out, int scene);
std::filesystem::path shard_record_file(const std::filesystem::path& out);  // OUT.parts/shards.json

// The header of the merged details file (detect_batch.hpp: an obj_id column with several
// models), kept in OUT.parts so that a merge by another process (`binpick merge`, --slurm's
// follower) writes the same one.
void write_details_header(const std::filesystem::path& out, const std::string& header);

// Whether the run plans picks: a marker in OUT.parts, so that a merge by another process writes
// OUT.picks.csv too.
void write_picks_marker(const std::filesystem::path& out, bool picks);

// Makes OUT.parts hold this run's fingerprint; a different one empties it first (its scene
// parts and its shard record).
void prepare_parts(const std::filesystem::path& out, const std::string& fingerprint);

// Whether the scene's results part is there (written last, it marks the scene done).
bool scene_done(const std::filesystem::path& out, int scene);

// Writes OUT, its details file and, with picks, its picks file (atomically) from the parts of `scenes`; returns the number
// of result rows. InputError naming the missing scenes if any part is missing.
std::size_t merge_detect_parts(const std::filesystem::path& out, const std::vector<int>& scenes);

}  // namespace binpick
