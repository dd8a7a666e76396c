// The detection options of the verbs that detect (`detect`, `run`, `tune`'s starting point):
// --params FILE and one option per row of the parameter table (host/detect/params/
// param_table.hpp), with the command line winning over the file.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>

#include "host/core/cli_fwd.hpp"
#include "host/detect/params/detect_params.hpp"

namespace binpick::cli {

struct DetectCliOptions {
  std::string params_file;
  DetectParams params;
  // Whole-number parameters are read wide, so a negative value reaches the range check with a
  // clear message.
  std::map<std::string, std::int64_t> counts;
  std::map<std::string, CLI::Option*> options;  // parameter name -> its option
};

// Adds --params and the parameter options to verb; `what` says what they set in the help
// ("detection", "the starting point's"). `skip`: parameters the verb does not take as options
// (tune measures every hypothesis, and has a --budget-ms of its own).
void add_detect_cli_options(CLI::App* verb, DetectCliOptions& o, const std::string& what,
                            const std::set<std::string>& skip = {});

// Defaults, then the file, then the options given. InputError for a bad file or value.
DetectParams resolve(const DetectCliOptions& o);

}  // namespace binpick::cli
