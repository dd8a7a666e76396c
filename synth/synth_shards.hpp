// A synth dataset made by shards (`synth --shard K/N`): each shard makes the bins at positions
// K-1, K-1+N, ... straight into DATASET/test/ (bins have their own seeds, so a bin is the same
// whichever process makes it), and DATASET/shards/shards.json records the whole batch. There is
// nothing to concatenate: the merge checks that every bin is there.
#pragma once

#include <filesystem>
#include <string>

#include "host/shards/shard_record.hpp"

namespace binpick {

std::filesystem::path synth_state_dir(const std::filesystem::path& dataset);  // DATASET/shards
std::filesystem::path synth_shard_record_file(const std::filesystem::path& dataset);

// Whether bin `bin` is complete (its scene_gt.json is written last, by a rename of the bin).
bool bin_done(const std::filesystem::path& dataset, int bin);

// Bins 0 .. bins-1 of DATASET in `shards` shards.
ShardRecord synth_shard_record(const std::filesystem::path& dataset, int bins, int shards);

// "DATASET: all N bins present"; InputError naming the missing bins and their shards.
std::string check_synth_shards(const ShardRecord& record);

}  // namespace binpick
