// synth.json: everything that shapes a dataset's bins except how many there are. A resumed or
// extended run must match it, or bins made with different settings would mix in one dataset.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "synth/synthesize.hpp"

namespace binpick {

struct ManifestInputs {
  std::string model;                         // the --model argument
  double diameter = 0;                       // of the model, mm
  std::vector<double> distractor_diameters;  // mm, in the order of options.distractors
  std::string bin_mesh_digest;               // of the --bin-mesh file's bytes; empty without one
};

nlohmann::json synth_manifest(const SynthOptions& options, const ManifestInputs& inputs);

// Writes out/synth.json, or checks the one there: throws InputError naming the first setting
// that differs.
void check_or_write_manifest(const std::filesystem::path& out, const nlohmann::json& want);

// FNV-1a (64 bits) of a file's bytes, as 16 hex digits: tells whether a bin mesh changed.
std::string file_digest(const std::filesystem::path& path);

}  // namespace binpick
