// The detection parameter file (`detect --params FILE`, written by `binpick tune`): a JSON object
// whose keys are the option names without the dashes, e.g.
//   {"ref-ratio": 0.2, "hypotheses": 5, "exclusion-ratio": 1.2, "crop-ratio": 1.0,
//    "cluster-distance": 0.144, "cluster-angle": 20, "peaks-per-ref": 3, "peak-ratio": 0.9,
//    "normal-ratio": 0.2}
// ('_' may be used for '-'); "roi" and "bin" are strings as on the command line
// ({"bin": "auto", "roi": "bin:-200,-150,0,200,150,300"}). Options given on the command line
// win over the file.
#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <string_view>

#include "host/detect/detector.hpp"

namespace binpick {

// The parameter names, as in the file and (with "--") on the command line.
const std::set<std::string>& detect_param_names();

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
