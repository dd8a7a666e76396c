// The detection parameter file (`detect --params FILE`, written by `binpick tune`): a JSON object
// whose keys are the parameters' names (param_table.hpp, without the dashes; '_' may stand for
// '-'), e.g. {"ref-ratio": 0.2, "hypotheses": 5, "over-rim": false, "bin": "auto"}. On/off
// parameters take true/false or 1/0; a parameter's older name is still read. Options given on
// the command line win over the file.
#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <string_view>

#include "host/detect/params/detect_params.hpp"

namespace binpick {

// Sets the parameters found in the file, except those named in `keep` (given on the command
// line). InputError naming the file for bad JSON, a key that is not a parameter, or a value of
// the wrong type (range checks are check(DetectParams)).
void apply_params_file(const std::filesystem::path& path, DetectParams& params,
                       const std::set<std::string>& keep = {});
// The same for the file's text held in memory; name is what errors call the file.
void apply_params_text(std::string_view text, const std::string& name, DetectParams& params,
                       const std::set<std::string>& keep = {});

// The same JSON object for params (keys sorted, one line): also the fingerprint of a batch run.
std::string params_json(const DetectParams& params);

}  // namespace binpick
