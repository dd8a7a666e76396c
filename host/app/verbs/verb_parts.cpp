// `binpick parts`: list the built-in parts, write them (or a given model) as mesh files, or
// describe a model file before using it.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <memory>

#include "host/app/options/model_options.hpp"
#include "host/app/verbs/verbs.hpp"
#include "host/core/error.hpp"
#include "host/formats/mesh/mesh_writers.hpp"
#include "host/core/diameter.hpp"
#include "host/core/mesh_geometry.hpp"
#include "host/core/mesh_topology.hpp"
#include "synth/parts/builtin_parts.hpp"

namespace binpick::cli {
namespace {

struct PartsArgs {
  bool list = false;
  bool info = false;
  std::string out;
  std::string format = "gltf";
  ModelArgs model;
};

void list_parts() {
  for (const auto& name : builtin_part_names())
    std::cout << name << '\t' << builtin_part_description(name) << '\n';
}

std::string vector_text(const Eigen::Vector3f& v) {
  return std::to_string(v.x()) + " " + std::to_string(v.y()) + " " + std::to_string(v.z());
}

void print_info(const ModelArgs& args) {
  const Model model = load_part(part_spec_of(args));
  const Mesh& mesh = model.mesh;
  const BoundingBox box = bounding_box(mesh.positions);
  const TopologyReport topology = check_topology(mesh);
  std::cout << "model: " << args.model << '\n'
            << "vertices: " << mesh.positions.size() << '\n'
            << "triangles: " << mesh.triangles.size() << '\n'
            << "bounding box min (mm): " << vector_text(box.min) << '\n'
            << "bounding box size (mm): " << vector_text(box.size()) << '\n'
            << "diameter (mm): " << exact_diameter(mesh.positions) << '\n'
            << "volume (mm^3, meaningful if closed): " << signed_volume(mesh) << '\n';
  if (topology.closed_and_oriented()) {
    std::cout << "closed and consistently oriented: yes\n";
  } else {
    std::cout << "closed and consistently oriented: no (" << topology.boundary_edges
              << " boundary edges, " << topology.misoriented_edges << " misoriented edges, "
              << topology.non_manifold_edges << " non-manifold edges, "
              << topology.degenerate_triangles << " degenerate triangles)\n";
  }
  std::cout << "known symmetries: " << model.symmetries.discrete.size() << " discrete, "
            << model.symmetries.continuous.size() << " continuous\n";
}

// One file per built-in part, or only the --model part (named after its file).
void write_parts(const PartsArgs& args) {
  const MeshFormat format = mesh_format_named(args.format);
  std::vector<std::pair<std::string, Mesh>> parts;
  if (!args.model.model.empty()) {
    constexpr std::string_view builtin = "builtin:";
    const std::string& spec = args.model.model;
    const std::string name = spec.starts_with(builtin)
                                 ? spec.substr(builtin.size())
                                 : std::filesystem::path(spec).stem().string();
    parts.emplace_back(name, load_part(part_spec_of(args.model)).mesh);
  } else {
    for (const auto& name : builtin_part_names()) parts.emplace_back(name, make_builtin_part(name));
  }
  // Only once every part has loaded, so a bad --model leaves nothing behind.
  const std::filesystem::path directory = args.out;
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) throw InputError("cannot create " + directory.string() + ": " + ec.message());
  for (const auto& [name, mesh] : parts) {
    const auto path = directory / (name + extension_of(format));
    write_mesh(path, mesh, format);
    std::cout << "wrote " << path.string() << '\n';
  }
}

}  // namespace

void add_parts_verb(CLI::App& app) {
  auto args = std::make_shared<PartsArgs>();
  CLI::App* verb = app.add_subcommand("parts",
                                      "built-in parts: list them, write them as mesh "
                                      "files, or describe a model file");
  verb->add_flag("--list", args->list,
                 "print the built-in parts, one per line: name<TAB>description");
  verb->add_option("--out", args->out,
                   "write each built-in part (or only --model) to DIR/NAME.EXT, creating DIR");
  verb->add_option("--format", args->format,
                   "file format for --out: gltf, glb, ply, ply-ascii, stl, obj")
      ->capture_default_str();
  verb->add_flag("--info", args->info,
                 "print size, diameter and closedness of --model (check a file before use)");
  add_model_options(verb, args->model, /*required=*/false);
  verb->callback([args] {
    if (!args->list && !args->info && args->out.empty())
      throw InputError("parts: nothing to do; use --list, --out DIR or --info --model MODEL");
    if (args->info && args->model.model.empty()) throw InputError("parts --info needs --model");
    if (args->list) list_parts();
    if (args->info) print_info(args->model);
    if (!args->out.empty()) write_parts(*args);
  });
}

}  // namespace binpick::cli
