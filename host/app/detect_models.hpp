// The models of `binpick detect`: --model given once or more, each a trained model (.ppfm) or a
// directory of them (or a BOP dataset's models/ folder of obj_NNNNNN.ply meshes, trained here),
// and the obj_id each one's rows carry: from --obj-id (once per --model, in the same order), else
// from a BOP file name obj_NNNNNN, else 1 for a single model (as before several were allowed).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "host/train/ppf_model.hpp"

namespace binpick::cli {

// One model file and the obj_id its detections are written with.
struct ModelSource {
  std::filesystem::path path;  // .ppfm, or a BOP obj_NNNNNN.ply to train
  int obj_id = 1;
};

// The obj_id a BOP file name states: obj_000012.ppfm or obj_000012.ply -> 12; none otherwise.
std::optional<int> obj_id_of_name(const std::filesystem::path& path);

// The models the --model arguments name, ascending by obj_id (the order of the results' rows).
// InputError, one message, for: --obj-id given for some --model but not all; --obj-id with a
// directory; an --obj-id that contradicts the file's BOP name; a model of several whose obj_id
// cannot be told; two models of one obj_id; a directory with no model; a missing path.
std::vector<ModelSource> resolve_model_sources(const std::vector<std::string>& models,
                                               const std::vector<int>& obj_ids);

// A model ready for detection: the trained model, the checksum of what it was made from (the
// resume fingerprint) and its obj_id.
struct LoadedModel {
  ModelSource source;
  PpfModel model;
  std::string checksum;
  double train_seconds = 0;  // > 0: trained here from a .ply (BOP models/ folder)
};

// Reads a .ppfm; trains a .ply with the default training parameters (docs/cli.md, train).
LoadedModel load_model_source(const ModelSource& source);

}  // namespace binpick::cli
