// The detection options of the verbs that detect (`run`, `tune`'s starting point): --params FILE
// and one option per detection parameter, with the command line winning over the file, exactly
// as `binpick detect` takes them.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "host/core/cli_fwd.hpp"

#include "host/detect/detector.hpp"

namespace binpick::cli {

struct DetectCliOptions {
  std::string params_file;
  DetectParams params;
  // Wide types, so a negative value reaches the range check with a clear message.
  std::int64_t hypotheses = 5, more_hypotheses = 5, peaks_per_ref = 3, candidates = 4, refine_iterations = 10,
               highest_up = 0, through_walls = 0, over_rim = 0, unique_votes = 0, spread_votes = 0,
               local_peaks = 1, instances = 0;
  std::map<std::string, CLI::Option*> options;  // parameter name -> its option
};

// Adds --params and the parameter options to verb; `what` says what they set in the help
// ("detection", "the starting point's").
void add_detect_cli_options(CLI::App* verb, DetectCliOptions& o, const std::string& what);

// Defaults, then the file, then the options given. InputError for a bad file or value.
DetectParams resolve(const DetectCliOptions& o);

}  // namespace binpick::cli
