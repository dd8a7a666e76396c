// Trained model files that are reused when their inputs have not changed, so `run`, `tune` and
// `demo` train once and a rerun resumes: next to MODEL.ppfm a small MODEL.ppfm.json records what
// it was trained from (the part's description, a checksum of its mesh, the training parameters
// and the file format version) and the model file's checksum.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "host/formats/mesh/load_model.hpp"
#include "host/train/ppf_model.hpp"

namespace binpick {

// A part as the pipeline verbs take it: the --model argument and its options.
struct PartSpec {
  std::string spec;  // file path or builtin:NAME
  ModelOptions options;
};

// One line naming the part and its options ("builtin:bracket", "a.stl unit-scale 1000"): what
// synth.json and the model's record store, so a resumed run can tell that its input is the same.
std::string describe(const PartSpec& part);

// FNV-1a 64 of bytes as 16 hex digits (the model checksum in detect's batch fingerprint).
std::string checksum_hex(std::string_view bytes);

struct TrainedModel {
  std::filesystem::path path;
  PpfModel model;
  std::string checksum;   // of the file's bytes
  bool reused = false;    // read back instead of trained
  PpfTrainStats stats;    // zero when reused
  double seconds = 0;     // training and writing, or reading
};

// The model of `mesh` trained with `params`, in `path`: read back if path and its record exist
// and the record matches (part description, mesh checksum, params, format version), otherwise
// trained and written (model first, record last, both atomically). InputError for bad params.
TrainedModel train_or_reuse(const Mesh& mesh, const std::string& part_description,
                            const PpfTrainParams& params, const std::filesystem::path& path);

}  // namespace binpick
