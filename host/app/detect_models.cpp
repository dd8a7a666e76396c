#include "host/app/detect_models.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <map>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/core/read_file.hpp"
#include "host/core/timing.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "host/train/model_store.hpp"
#include "host/train/ppf_model_file.hpp"

namespace binpick::cli {
namespace {

namespace fs = std::filesystem;

// The files of dir with the extension, by name (the directory's order is the file system's).
std::vector<fs::path> files_with_extension(const fs::path& dir, const std::string& ext) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ext) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

// A directory's models: its .ppfm files, or, in a BOP models/ folder (models_info.json beside
// them) without any, its obj_NNNNNN.ply meshes. Each takes its obj_id from its name.
std::vector<ModelSource> directory_models(const fs::path& dir) {
  std::vector<fs::path> files = files_with_extension(dir, ".ppfm");
  if (files.empty() && fs::is_regular_file(dir / "models_info.json")) {
    files = files_with_extension(dir, ".ply");
    std::erase_if(files, [](const fs::path& p) { return !obj_id_of_name(p); });
  }
  if (files.empty())
    throw InputError(fmt::format(
        "--model {}: the directory holds no model (.ppfm files from `binpick train`, or a BOP "
        "models/ folder: models_info.json and obj_NNNNNN.ply)",
        dir.string()));
  std::vector<ModelSource> models;
  for (const fs::path& file : files) {
    const auto id = obj_id_of_name(file);
    if (!id)
      throw InputError(fmt::format(
          "--model {}: cannot tell the obj_id of {}: name it obj_NNNNNN.ppfm (BOP's name) or "
          "give it as --model FILE --obj-id N",
          dir.string(), file.filename().string()));
    models.push_back({file, *id});
  }
  return models;
}

}  // namespace

std::optional<int> obj_id_of_name(const fs::path& path) {
  const std::string stem = path.stem().string();
  if (stem.size() != 10 || !stem.starts_with("obj_")) return std::nullopt;
  int id = 0;
  const char* digits = stem.data() + 4;
  const auto [end, ec] = std::from_chars(digits, stem.data() + stem.size(), id);
  if (ec != std::errc() || end != stem.data() + stem.size() || id < 1 || *digits == '-' ||
      *digits == '+')
    return std::nullopt;
  return id;
}

std::vector<ModelSource> resolve_model_sources(const std::vector<std::string>& models,
                                               const std::vector<int>& obj_ids) {
  if (models.empty()) throw InputError("--model is required");
  if (!obj_ids.empty() && obj_ids.size() != models.size())
    throw InputError(fmt::format(
        "{} --model but {} --obj-id: give --obj-id once per --model, in the same order, or "
        "not at all (the obj_id then comes from a BOP name obj_NNNNNN.ppfm)",
        models.size(), obj_ids.size()));
  std::vector<ModelSource> sources;
  for (std::size_t i = 0; i < models.size(); ++i) {
    const fs::path path = models[i];
    if (fs::is_directory(path)) {
      if (!obj_ids.empty())
        throw InputError(fmt::format(
            "--obj-id {} is given for the directory {}: the models of a directory take their "
            "obj_ids from their names (obj_NNNNNN.ppfm)",
            obj_ids[i], path.string()));
      const auto found = directory_models(path);
      sources.insert(sources.end(), found.begin(), found.end());
      continue;
    }
    require_regular_file(path);
    const auto named = obj_id_of_name(path);
    if (!obj_ids.empty()) {
      if (obj_ids[i] < 1)
        throw InputError(fmt::format("--obj-id {} must be at least 1", obj_ids[i]));
      if (named && *named != obj_ids[i])
        throw InputError(fmt::format("--obj-id {} contradicts the name of --model {} (obj_id {})",
                                     obj_ids[i], path.string(), *named));
      sources.push_back({path, obj_ids[i]});
    } else if (named) {
      sources.push_back({path, *named});
    } else if (models.size() == 1) {
      sources.push_back({path, 1});  // one model: obj_id 1, as before several were allowed
    } else {
      throw InputError(fmt::format(
          "cannot tell the obj_id of --model {}: with several models give --obj-id once per "
          "--model, or name the files obj_NNNNNN.ppfm",
          path.string()));
    }
  }
  std::stable_sort(sources.begin(), sources.end(),
                   [](const ModelSource& a, const ModelSource& b) { return a.obj_id < b.obj_id; });
  for (std::size_t i = 1; i < sources.size(); ++i)
    if (sources[i].obj_id == sources[i - 1].obj_id)
      throw InputError(fmt::format("two models have obj_id {}: {} and {}", sources[i].obj_id,
                                   sources[i - 1].path.string(), sources[i].path.string()));
  return sources;
}

LoadedModel load_model_source(const ModelSource& source) {
  LoadedModel loaded;
  loaded.source = source;
  if (source.path.extension() != ".ply") {
    const std::string bytes = read_file_bytes(source.path);
    loaded.model = parse_ppf_model(bytes, source.path.string());
    loaded.checksum = checksum_hex(bytes);
    return loaded;
  }
  // A BOP model in mm, trained as `binpick train` does by default.
  const auto start = std::chrono::steady_clock::now();
  const Mesh mesh = load_model(source.path.string(), ModelOptions{});
  loaded.model = train_ppf_model(mesh, PpfTrainParams{});
  loaded.train_seconds = seconds_since(start);
  loaded.checksum = checksum_hex(serialize_ppf_model(loaded.model));  // as its .ppfm's
  return loaded;
}

}  // namespace binpick::cli
