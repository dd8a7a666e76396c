// The .ppfm model file: a trained PpfModel, so detection does not retrain.
//
// Layout (little-endian, 4-byte fields unless noted):
//   magic "BINPKPPF" (8 bytes), format version, header size in bytes,
//   diameter, voxel size, bp_ppf_quant (32 bytes: max_distance, dist_step, angle_step, n_dist,
//   n_angle, n_alpha, 2 reserved), point count, key count, entry count (8 bytes),
//   checksum of the payload (8 bytes);
//   payload: points (3 floats each), normals (3 floats each), offsets (key count + 1 uint32),
//   entries (uint32 point, float alpha); from version 2 on, the part's symmetries: continuous
//   count, discrete count (uint32 each), each continuous symmetry as axis and offset
//   (6 doubles), each discrete one as the top three rows of its 4x4 transform (12 doubles,
//   row-major); from version 3 on, the refinement points: count (uint32), points (3 floats
//   each), normals (3 floats each); from version 4 on, the look-alikes (lookalikes.hpp):
//   count (uint32), each as the top three rows of its 4x4 transform (12 doubles, row-major), and
//   their probes (lookalike_probes.hpp): count (uint32), points (3 floats each), normals (3 floats
//   each), the look-alike of each (uint32 each); from version 5 on, the edge probes
//   (edge_probes.hpp): count (uint32), points (3 floats each), normals (3 floats each); from
//   version 6 on, each edge probe's kind (1 byte each: 0 a face probe, 1 a rim probe); from
//   version 7 on, the grasps (grasp.hpp): count (uint32), each as its kind (uint32: 0 suction,
//   1 parallel) and 10 doubles (point, approach, closing axis, size).
// Version 1 to 6 files (before symmetries, refinement points, probes, edge probes, their kinds,
// grasps)
// are still read, without them (the look-alikes found again from the points; a version 5 file's
// edge probes all face probes): the table is the same.
// Readers refuse other versions: a changed format or feature
// convention needs a retrain.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "host/train/ppf_model.hpp"

namespace binpick {

inline constexpr std::uint32_t kPpfModelFormatVersion = 7;
inline constexpr std::uint32_t kPpfModelOldestReadVersion = 1;

// The file's bytes; identical for identical models. Older versions (tests of old files) leave
// out what they did not have; a version outside those read is a logic error.
std::string serialize_ppf_model(const PpfModel& model,
                                std::uint32_t version = kPpfModelFormatVersion);

// Parses bytes read from `name` (used in messages). Throws InputError: "model file NAME is
// truncated", "... is not a binpick PPF model", "... was written by format version N, this
// binpick reads versions 1 to 5: retrain", "... is corrupt (...)".
PpfModel parse_ppf_model(std::string_view bytes, const std::string& name);

// Writes through write_file_atomically (no partial file on error).
void write_ppf_model(const std::filesystem::path& path, const PpfModel& model);

PpfModel read_ppf_model(const std::filesystem::path& path);

}  // namespace binpick
