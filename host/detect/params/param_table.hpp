// The one table of detection parameters: name, member, type, range, group and help of each.
// The command line's options (host/app/options/detect_options.cpp), the --params file's reader and
// writer (params_file.hpp), validation (detect_params.hpp) and the table in docs/parameters.md
// (checked by tests/detect/params/test_param_table.cpp) all come from it; the defaults are
// DetectParams' own.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <variant>

#include "host/detect/params/detect_params.hpp"

namespace binpick {

// A closed range [lo, hi], open at lo where lo_open, or 0 beside it where or_zero
// ("{0} or [1, 100]").
struct ParamRange {
  double lo = 0, hi = 0;
  bool lo_open = false;
  bool or_zero = false;
  const char* unit = "";  // appended to the range's text ("degrees")
};

using ParamMember = std::variant<double DetectParams::*, std::uint32_t DetectParams::*,
                                 bool DetectParams::*, std::string DetectParams::*>;

struct ParamInfo {
  const char* name;   // --name on the command line, the key in a --params file
  ParamMember member;
  ParamRange range;   // numbers only
  const char* group;  // hypotheses, region, scene, voting, clustering, refinement, verification
  const char* help;   // one sentence or two: what it does, what 0 means where it is "off"
  const char* old_name = nullptr;  // a name it had before, still read from --params files
};

std::span<const ParamInfo> detect_param_table();
// nullptr if no parameter has that name (or old name).
const ParamInfo* find_param(const std::string& name);

bool is_flag(const ParamInfo& p);  // on/off: --name / --no-name
bool is_text(const ParamInfo& p);
bool is_count(const ParamInfo& p);  // a whole number
// "(0, 1]", "{0} or [1, 100]", "[0, 180] degrees"; "on/off" for flags, "text" for texts.
std::string range_text(const ParamInfo& p);
// The parameter's value in params as a double (numbers and flags).
double number_of(const ParamInfo& p, const DetectParams& params);
// The default, as docs and --help show it ("0.2", "5", "on", "auto", "" for an empty text).
std::string default_text(const ParamInfo& p);
// The docs' table (docs/parameters.md, between its "param-table" markers), one row a parameter.
std::string param_table_markdown();

}  // namespace binpick
