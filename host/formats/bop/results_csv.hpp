// The BOP results CSV (bop_toolkit's format; docs/formats.md): what `detect` writes and
// `eval` reads.
//
//   scene_id,im_id,obj_id,score,R,t,time
//   0,0,1,812,r11 r12 r13 r21 r22 r23 r31 r32 r33,tx ty tz,0.413
//
// R is row-major (model to camera), t in mm, time in seconds for the whole image (the same on
// each of its rows), score the vote count. One row per hypothesis, best first.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace binpick::bop {

struct ResultRow {
  int scene_id = 0, im_id = 0, obj_id = 1;
  double score = 0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  double time = 0;
};

inline constexpr const char* kResultsCsvHeader = "scene_id,im_id,obj_id,score,R,t,time";

// The CSV text of rows (header first, one line per row, '\n' line ends). Numbers are written in
// their shortest round-trip form, independent of the locale, so equal rows give equal bytes.
std::string format_results_csv(const std::vector<ResultRow>& rows);

// One row as it appears in the file, without the line end.
std::string format_result_row(const ResultRow& row);

// Writes format_results_csv(rows) through write_file_atomically.
void write_results_csv(const std::filesystem::path& path, const std::vector<ResultRow>& rows);

// Parses CSV text read from `name` (used in messages). Throws InputError "NAME line L: ..."
// for a missing or different header, a wrong column count, an R without exactly 9 or a t
// without exactly 3 numbers, a number that does not parse or is not finite, or a non-integer id.
// Accepts '\r\n' line ends and a missing final line end; blank lines are skipped.
std::vector<ResultRow> parse_results_csv(const std::string& text, const std::string& name);

// Reads and parses path (InputError if it cannot be read).
std::vector<ResultRow> read_results_csv(const std::filesystem::path& path);

}  // namespace binpick::bop
