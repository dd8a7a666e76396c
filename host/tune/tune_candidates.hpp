// The candidates of one `tune --slurm` job array, in a file its tasks read
// (OUT/shards/points-HASH.json, named by its content, so an array still queued from an
// earlier submission never reads another batch's list):
//   {"points": [{"ref-ratio": 0.02, "cluster-distance": 0.144, ..., "distance-steps": 20,
//                "key": "CHECKSUM"}, ...]}
// Each point is the value of every tune axis; the rest of the parameters are the tune's
// starting point, given to every task by the same command line. The key (the checksum of the
// point's canonical text) catches a task run with other options.
#pragma once

#include <filesystem>
#include <vector>

#include "host/tune/tune_space.hpp"

namespace binpick {

// Writes the file (atomically) into `dir` and returns its path.
std::filesystem::path write_candidates(const std::filesystem::path& dir,
                                       const std::vector<TunePoint>& points);

// The points of FILE, each from `start` with the file's axis values. InputError naming the file
// if it is missing or malformed, or if a point's key differs (other options than the file's).
std::vector<TunePoint> read_candidates(const std::filesystem::path& file, const TunePoint& start);

}  // namespace binpick
