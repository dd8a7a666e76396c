#include "host/formats/bop/results_csv.hpp"

#include <charconv>
#include <cmath>
#include <string_view>

#include "host/core/error.hpp"
#include "host/core/atomic_file.hpp"
#include "host/core/read_file.hpp"
#include "host/formats/mesh/text_numbers.hpp"

namespace binpick::bop {
namespace {

[[noreturn]] void fail(const std::string& name, std::size_t line, const std::string& what) {
  throw InputError(name + " line " + std::to_string(line) + ": " + what);
}

std::vector<std::string_view> split(std::string_view text, char sep, bool skip_empty) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  while (true) {
    std::size_t end = text.find(sep, start);
    std::string_view part = text.substr(start, end == std::string_view::npos ? text.npos : end - start);
    if (!(skip_empty && part.empty())) parts.push_back(part);
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return parts;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// A finite double; from_chars does not accept a leading '+', which bop_toolkit never writes.
double parse_double(std::string_view s, const std::string& name, std::size_t line,
                    const char* column) {
  s = trim(s);
  double value = 0;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size())
    fail(name, line, std::string(column) + ": '" + std::string(s) + "' is not a number");
  if (!std::isfinite(value)) fail(name, line, std::string(column) + " is not finite");
  return value;
}

int parse_int(std::string_view s, const std::string& name, std::size_t line, const char* column) {
  s = trim(s);
  int value = 0;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size())
    fail(name, line, std::string(column) + ": '" + std::string(s) + "' is not an integer");
  return value;
}

}  // namespace

std::string format_result_row(const ResultRow& row) {
  std::string out;
  append_number(out, row.scene_id);
  out += ',';
  append_number(out, row.im_id);
  out += ',';
  append_number(out, row.obj_id);
  out += ',';
  append_number(out, row.score);
  out += ',';
  for (int i = 0; i < 9; ++i) {
    if (i) out += ' ';
    append_number(out, row.R(i / 3, i % 3));
  }
  out += ',';
  for (int i = 0; i < 3; ++i) {
    if (i) out += ' ';
    append_number(out, row.t(i));
  }
  out += ',';
  append_number(out, row.time);
  return out;
}

std::string format_results_csv(const std::vector<ResultRow>& rows) {
  std::string out = kResultsCsvHeader;
  out += '\n';
  for (const ResultRow& row : rows) {
    out += format_result_row(row);
    out += '\n';
  }
  return out;
}

void write_results_csv(const std::filesystem::path& path, const std::vector<ResultRow>& rows) {
  const std::string text = format_results_csv(rows);
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

std::vector<ResultRow> parse_results_csv(const std::string& text, const std::string& name) {
  std::vector<ResultRow> rows;
  bool header_seen = false;
  std::size_t line_no = 0;
  for (std::string_view line : split(text, '\n', false)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (trim(line).empty()) continue;
    if (!header_seen) {
      if (trim(line) != kResultsCsvHeader)
        fail(name, line_no, std::string("expected the header '") + kResultsCsvHeader + "'");
      header_seen = true;
      continue;
    }
    const auto columns = split(line, ',', false);
    if (columns.size() != 7)
      fail(name, line_no, "expected 7 columns, found " + std::to_string(columns.size()));
    ResultRow row;
    row.scene_id = parse_int(columns[0], name, line_no, "scene_id");
    row.im_id = parse_int(columns[1], name, line_no, "im_id");
    row.obj_id = parse_int(columns[2], name, line_no, "obj_id");
    row.score = parse_double(columns[3], name, line_no, "score");
    const auto r = split(trim(columns[4]), ' ', true);
    if (r.size() != 9) fail(name, line_no, "R needs 9 numbers, found " + std::to_string(r.size()));
    for (int i = 0; i < 9; ++i) row.R(i / 3, i % 3) = parse_double(r[i], name, line_no, "R");
    const auto t = split(trim(columns[5]), ' ', true);
    if (t.size() != 3) fail(name, line_no, "t needs 3 numbers, found " + std::to_string(t.size()));
    for (int i = 0; i < 3; ++i) row.t(i) = parse_double(t[i], name, line_no, "t");
    row.time = parse_double(columns[6], name, line_no, "time");
    rows.push_back(row);
  }
  if (!header_seen) throw InputError(name + ": empty results file (no header)");
  return rows;
}

std::vector<ResultRow> read_results_csv(const std::filesystem::path& path) {
  return parse_results_csv(read_file_bytes(path), path.string());
}

}  // namespace binpick::bop
