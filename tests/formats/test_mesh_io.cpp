// Model files: every writer round-trips through load_model, the readers handle the variants of
// each format (PLY encodings and types, glTF node hierarchies), and every kind of bad input is
// an InputError, never a crash.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>

#include "host/core/error.hpp"
#include "host/core/atomic_file.hpp"
#include "host/formats/bop/bop_models.hpp"
#include "host/formats/mesh/little_endian.hpp"
#include "host/formats/mesh/mesh_writers.hpp"
#include "host/formats/mesh/point_cloud_ply.hpp"
#include "host/core/read_file.hpp"
#include "host/core/diameter.hpp"
#include "host/app/options/model_options.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "host/core/mesh_geometry.hpp"
#include "host/core/mesh_topology.hpp"
#include "synth/parts/builtin_parts.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;

class MeshIo : public testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() / ("binpick_mesh_io_" + std::to_string(::getpid()) + "_" +
                                     testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path file(const std::string& name, const std::string& bytes) {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }

  fs::path dir_;
};

std::string error_of(const std::string& spec, const ModelOptions& options = {}) {
  try {
    cli::load_part({spec, options});
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void expect_same_triangles(const Mesh& expected, const Mesh& actual, bool compare_normals) {
  ASSERT_EQ(expected.triangles.size(), actual.triangles.size());
  for (std::size_t t = 0; t < expected.triangles.size(); ++t) {
    for (int c = 0; c < 3; ++c) {
      const auto e = expected.triangles[t][c], a = actual.triangles[t][c];
      ASSERT_LT((expected.positions[e] - actual.positions[a]).norm(), 1e-5f) << "triangle " << t;
      if (compare_normals) {
        ASSERT_LT((expected.normals[e] - actual.normals[a]).norm(), 1e-5f);
      }
    }
  }
}

// ---- writers and round trips -------------------------------------------------------------

TEST_F(MeshIo, EveryFormatRoundTrips) {
  const Mesh part = make_builtin_part("tee");
  for (const char* name : {"ply", "ply-ascii", "stl", "obj", "gltf", "glb"}) {
    SCOPED_TRACE(name);
    const MeshFormat format = mesh_format_named(name);
    const fs::path path = dir_ / (std::string("part_") + name + extension_of(format));
    write_mesh(path, part, format);
    const Mesh loaded = load_model(path.string(), {});
    // STL keeps no vertex normals: its are recomputed, and match only on flat faces.
    expect_same_triangles(part, loaded, format != MeshFormat::stl);
    EXPECT_TRUE(check_topology(loaded).closed_and_oriented());
  }
}

TEST_F(MeshIo, StlRoundTripRecoversSharpEdgesAndWeldsTheSoup) {
  const Mesh part = make_builtin_part("bracket");
  write_stl(dir_ / "bracket.stl", part);
  const Mesh loaded = load_model((dir_ / "bracket.stl").string(), {});
  // Sharp edges must not be averaged (that would put normals 45 degrees off); the hole walls
  // are smooth, their facets within half a sampling step of the vertex normals.
  for (const auto& t : loaded.triangles) {
    const Eigen::Vector3f face = (loaded.positions[t[1]] - loaded.positions[t[0]])
                                     .cross(loaded.positions[t[2]] - loaded.positions[t[0]])
                                     .normalized();
    for (auto v : t)
      ASSERT_GT(face.dot(loaded.normals[v]), std::cos(10 * std::numbers::pi_v<float> / 180));
  }
  EXPECT_LT(loaded.positions.size(), 3 * loaded.triangles.size());
}

TEST_F(MeshIo, BinaryStlIsNotMistakenForAscii) {
  const Mesh part = make_builtin_part("bolt");
  write_stl(dir_ / "bolt.stl", part);
  std::string bytes = read_file_bytes(dir_ / "bolt.stl");
  bytes.replace(0, 5, "solid");  // some exporters start binary headers with "solid"
  const fs::path path = file("solid_header.stl", bytes);
  EXPECT_EQ(load_model(path.string(), {}).triangles.size(), part.triangles.size());
}

TEST_F(MeshIo, AsciiStlWithQuadLoop) {
  const fs::path path = file("quad.stl",
                             "solid test\n"
                             " facet normal 0 0 0\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n"
                             "   vertex 1 1 0\n   vertex 0 1 0\n  endloop\n endfacet\n"
                             "endsolid test\n");
  const Mesh mesh = load_model(path.string(), {});
  EXPECT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.positions.size(), 4u);  // welded
  for (const auto& n : mesh.normals) EXPECT_NEAR(n.z(), 1.0f, 1e-6f);
}

TEST_F(MeshIo, UnitScaleAndDiameter) {
  const Mesh part = make_builtin_part("bolt");
  write_ply(dir_ / "bolt.ply", part);
  ModelOptions metres;
  metres.unit_scale = 1000;
  EXPECT_NEAR(exact_diameter(load_model((dir_ / "bolt.ply").string(), metres).positions), 52000,
              0.1);
  ModelOptions sized;
  sized.unit_scale = 1000;
  sized.diameter = 26;
  const Mesh half = load_model((dir_ / "bolt.ply").string(), sized);
  EXPECT_NEAR(exact_diameter(half.positions), 26, 1e-4);
  // Uniformly about the origin: every vertex halves.
  EXPECT_LT((half.positions[7] - part.positions[7] / 2).norm(), 1e-5f);
}

// A part read in the wrong unit is named: the bolt (52 mm) as if its file were in metres and
// read as mm, or in micrometres read as mm; the bolt itself, and the bolt scaled to 2 mm
// across (a small part, but a part), pass.
TEST(ImplausibleSize, NamesAFileInTheWrongUnit) {
  Mesh bolt = make_builtin_part("bolt");
  EXPECT_EQ(implausible_size(bolt), "");
  Mesh metres = bolt, micrometres = bolt, small = bolt;
  for (auto& p : metres.positions) p /= 1000.0f;
  for (auto& p : micrometres.positions) p *= 1000.0f;
  for (auto& p : small.positions) p *= 2.0f / 52.0f;
  EXPECT_NE(implausible_size(metres).find("--unit-scale 1000"), std::string::npos)
      << implausible_size(metres);
  EXPECT_NE(implausible_size(micrometres).find("--unit-scale 0.001"), std::string::npos)
      << implausible_size(micrometres);
  EXPECT_EQ(implausible_size(small), "");
  EXPECT_EQ(implausible_size(Mesh{}), "");
}

TEST_F(MeshIo, AtomicWriteLeavesNothingOnFailure) {
  const fs::path target = dir_ / "out.bin";
  EXPECT_THROW(write_file_atomically(target,
                                     [](std::ostream& out) {
                                       out << "partial";
                                       throw InputError("writer failed");
                                     }),
               InputError);
  EXPECT_TRUE(fs::is_empty(dir_)) << "no file, not even the temporary one";

  write_file_atomically(target, [](std::ostream& out) { out << "old"; });
  EXPECT_THROW(write_file_atomically(target, [](std::ostream&) { throw std::runtime_error("x"); }),
               std::runtime_error);
  EXPECT_EQ(read_file_bytes(target), "old") << "a failed write keeps the previous file";
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);

  EXPECT_THROW(write_file_atomically(dir_ / "missing" / "x", [](std::ostream& out) { out << 1; }),
               InputError);
  EXPECT_THROW(write_ply(dir_ / "missing" / "x.ply", make_builtin_part("bolt")), InputError);
}

TEST_F(MeshIo, BopModels) {
  const Model bolt = cli::load_part({"builtin:bolt", {}});
  write_bop_models(dir_, make_builtin_part("bracket"), 1);
  write_bop_models(dir_, bolt.mesh, 2, bolt.symmetries);

  const std::string ply = read_file_bytes(dir_ / "models" / "obj_000002.ply");
  const std::string header = ply.substr(0, ply.find("end_header"));
  EXPECT_NE(header.find("format binary_little_endian 1.0"), std::string::npos);
  EXPECT_NE(header.find("property float nx"), std::string::npos);
  EXPECT_NE(header.find("property list uchar int vertex_indices"), std::string::npos);
  expect_same_triangles(bolt.mesh, load_model((dir_ / "models" / "obj_000002.ply").string(), {}),
                        true);

  const auto info = nlohmann::json::parse(read_file_bytes(dir_ / "models" / "models_info.json"));
  ASSERT_TRUE(info.contains("1")) << "writing object 2 keeps object 1";
  const auto& entry = info["2"];
  EXPECT_NEAR(entry["diameter"].get<double>(), 52, 1e-4);
  const BoundingBox box = bounding_box(bolt.mesh.positions);
  EXPECT_NEAR(entry["min_z"].get<double>(), box.min.z(), 1e-5);
  EXPECT_NEAR(entry["size_x"].get<double>(), box.size().x(), 1e-5);
  ASSERT_EQ(entry["symmetries_discrete"].size(), 5u);
  EXPECT_EQ(entry["symmetries_discrete"][0].size(), 16u);
  EXPECT_FALSE(info["1"].contains("symmetries_discrete"));
  EXPECT_FALSE(entry.contains("symmetries_continuous"));
}

TEST_F(MeshIo, PointCloudPlyRoundTrip) {
  PointCloud cloud{{{1, 2, 3}, {4, 5, 6}}, {{0, 0, 1}, {1, 0, 0}}};
  write_point_cloud_ply(dir_ / "cloud.ply", cloud);
  const PointCloud back = read_point_cloud_ply(dir_ / "cloud.ply");
  ASSERT_EQ(back.points.size(), 2u);
  EXPECT_EQ(back.points[1], cloud.points[1]);
  EXPECT_EQ(back.normals[1], cloud.normals[1]);
}

// ---- PLY variants --------------------------------------------------------------------------

TEST_F(MeshIo, AsciiPlyWithQuadsExtraPropertiesAndNonUnitNormals) {
  const fs::path path =
      file("quads.ply",
           "ply\r\nformat ascii 1.0\ncomment a quad and a triangle\n"
           "element vertex 5\nproperty double x\nproperty double y\nproperty double z\n"
           "property float confidence\nproperty float nx\nproperty float ny\n"
           "property float nz\nelement face 2\nproperty list uchar uint vertex_indices\n"
           "property uchar red\nelement material 1\nproperty list int int ids\n"
           "end_header\n"
           "0 0 0 0.5 0 0 3\n1 0 0 0.5 0 0 2\n1 1 0 0.5 0 0 5\n0 1 0 0.5 0 0 1\n"
           "+2 2 1e-1 1 0 0 0.5\n"
           "4 0 1 2 3 255\n3 1 2 4 7\n2 10 20\n");
  const Mesh mesh = load_model(path.string(), {});
  EXPECT_EQ(mesh.triangles.size(), 3u);
  EXPECT_FLOAT_EQ(mesh.positions[4].z(), 0.1f);
  for (const auto& n : mesh.normals) EXPECT_NEAR(n.norm(), 1.0f, 1e-6f);
  EXPECT_FLOAT_EQ(mesh.normals[0].z(), 1.0f);

  const std::string no_final_newline =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float "
      "z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 "
      "0 1 2";
  EXPECT_EQ(parse_model(no_final_newline, "ply", {}).triangles.size(), 1u);
}

// A binary PLY of one tetrahedron with the given encoding and types.
std::string tetrahedron_ply(bool big_endian, const std::string& coordinate,
                            const std::string& count, const std::string& index) {
  std::string out =
      "ply\nformat " + std::string(big_endian ? "binary_big_endian" : "binary_little_endian") +
      " 1.0\nelement vertex 4\nproperty " + coordinate + " x\nproperty " + coordinate +
      " y\nproperty " + coordinate + " z\nelement face 4\nproperty list " + count + " " + index +
      " vertex_indices\nend_header\n";
  auto put = [&](const std::string& type, double value) {
    std::string bytes;
    if (type == "uchar" || type == "uint8" || type == "char")
      bytes = std::string(1, char(value));
    else if (type == "short" || type == "ushort")
      append_little_endian(bytes, std::uint16_t(value));
    else if (type == "int" || type == "uint")
      append_little_endian(bytes, std::uint32_t(value));
    else if (type == "float")
      append_little_endian(bytes, float(value));
    else
      append_little_endian(bytes, value);
    if (big_endian) std::reverse(bytes.begin(), bytes.end());
    out += bytes;
  };
  for (const auto& p : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10, 0, 0),
                        Eigen::Vector3d(0, 10, 0), Eigen::Vector3d(0, 0, 10)}) {
    for (double v : p) put(coordinate, v);
  }
  for (const auto& f :
       {std::array{0, 2, 1}, std::array{0, 1, 3}, std::array{0, 3, 2}, std::array{1, 2, 3}}) {
    put(count, 3);
    for (int v : f) put(index, v);
  }
  return out;
}

TEST_F(MeshIo, BinaryPlyEveryEndiannessAndType) {
  for (bool big : {false, true}) {
    for (const std::string coordinate : {"float", "double", "short"}) {
      for (const std::string count : {"uchar", "ushort", "int"}) {
        for (const std::string index : {"int", "uint", "ushort", "uint8"}) {
          SCOPED_TRACE(coordinate + " " + count + " " + index + (big ? " big" : " little"));
          const Mesh mesh = parse_model(tetrahedron_ply(big, coordinate, count, index), "ply", {});
          ASSERT_EQ(mesh.triangles.size(), 4u);
          EXPECT_TRUE(check_topology(mesh).closed_and_oriented());
          EXPECT_NEAR(signed_volume(mesh), 1000.0 / 6, 1e-3);
        }
      }
    }
  }
}

// ---- glTF node hierarchy and --mesh --------------------------------------------------------

// Two meshes in one assembly: "plate" (a unit square, 2 triangles) under node "left" and
// "wedge" (a tetrahedron, 4 triangles) under node "right"; both below "assembly", scaled 10.
tinygltf::Model two_mesh_assembly() {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.buffers.emplace_back();
  auto add = [&](const std::vector<float>& positions, const std::vector<std::uint16_t>& indices,
                 const std::string& name) {
    auto& data = model.buffers[0].data;
    const std::size_t position_offset = data.size();
    data.resize(data.size() + positions.size() * 4);
    std::memcpy(data.data() + position_offset, positions.data(), positions.size() * 4);
    const std::size_t index_offset = data.size();
    data.resize(data.size() + indices.size() * 2 + (indices.size() % 2) * 2);  // keep 4-alignment
    std::memcpy(data.data() + index_offset, indices.data(), indices.size() * 2);
    tinygltf::BufferView pv, iv;
    pv.buffer = iv.buffer = 0;
    pv.byteOffset = position_offset;
    pv.byteLength = positions.size() * 4;
    iv.byteOffset = index_offset;
    iv.byteLength = indices.size() * 2;
    model.bufferViews.push_back(pv);
    model.bufferViews.push_back(iv);
    tinygltf::Accessor pa, ia;
    pa.bufferView = int(model.bufferViews.size()) - 2;
    pa.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    pa.type = TINYGLTF_TYPE_VEC3;
    pa.count = positions.size() / 3;
    pa.minValues = {0, 0, 0};
    pa.maxValues = {1, 1, 1};
    ia.bufferView = int(model.bufferViews.size()) - 1;
    ia.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    ia.type = TINYGLTF_TYPE_SCALAR;
    ia.count = indices.size();
    model.accessors.push_back(pa);
    model.accessors.push_back(ia);
    tinygltf::Primitive primitive;
    primitive.attributes["POSITION"] = int(model.accessors.size()) - 2;
    primitive.indices = int(model.accessors.size()) - 1;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    tinygltf::Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(primitive);
    model.meshes.push_back(mesh);
  };
  add({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, {0, 1, 2, 0, 2, 3}, "plate");
  add({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}, "wedge");

  tinygltf::Node assembly, left, right, unused;
  assembly.name = "assembly";
  assembly.scale = {10, 10, 10};
  assembly.children = {1, 2};
  left.name = "left";
  left.mesh = 0;
  left.translation = {-5, 0, 0};
  right.name = "right";
  right.mesh = 1;
  // Column-major: a quarter turn about z, then a move of +5 in x.
  right.matrix = {0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1};
  model.nodes = {assembly, left, right};
  tinygltf::Scene scene;
  scene.nodes = {0};
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  return model;
}

void save(const tinygltf::Model& model, const fs::path& path, bool binary) {
  tinygltf::TinyGLTF writer;
  std::ofstream out(path, std::ios::binary);
  ASSERT_TRUE(writer.WriteGltfSceneToStream(&model, out, false, binary));
}

TEST_F(MeshIo, GltfAppliesTheNodeHierarchy) {
  for (bool binary : {false, true}) {
    const fs::path path = dir_ / (binary ? "assembly.glb" : "assembly.gltf");
    save(two_mesh_assembly(), path, binary);
    const Mesh all = load_model(path.string(), {});
    EXPECT_EQ(all.triangles.size(), 6u);
    const BoundingBox box = bounding_box(all.positions);
    // plate: x in (-5 + [0,1]) * 10; wedge turned: x in (5 + [-1, 0]) * 10 ... up to 50.
    EXPECT_NEAR(box.min.x(), -50, 1e-4);
    EXPECT_NEAR(box.max.x(), 50, 1e-4);
    EXPECT_NEAR(box.max.z(), 10, 1e-4);

    ModelOptions right;
    right.mesh_name = "right";
    const Mesh wedge = load_model(path.string(), right);
    ASSERT_EQ(wedge.triangles.size(), 4u);
    // The wedge's (1, 0, 0) corner: turned to (0, 1, 0), moved to (5, 1, 0), scaled by 10.
    bool found = false;
    for (const auto& p : wedge.positions) found |= (p - Eigen::Vector3f(50, 10, 0)).norm() < 1e-4f;
    EXPECT_TRUE(found);
    EXPECT_NEAR(signed_volume(wedge), 1000.0 / 6, 1e-3);

    ModelOptions by_mesh_name;
    by_mesh_name.mesh_name = "wedge";
    expect_same_triangles(wedge, load_model(path.string(), by_mesh_name), false);

    ModelOptions subtree;
    subtree.mesh_name = "assembly";
    EXPECT_EQ(load_model(path.string(), subtree).triangles.size(), 6u);

    ModelOptions unknown;
    unknown.mesh_name = "gear";
    const std::string message = error_of(path.string(), unknown);
    for (const char* name : {"gear", "assembly", "left", "right", "plate", "wedge"})
      EXPECT_NE(message.find(name), std::string::npos) << message;
  }
}

TEST_F(MeshIo, GltfWithExternalBuffer) {
  const fs::path path = dir_ / "external.gltf";
  tinygltf::TinyGLTF writer;
  const tinygltf::Model model = two_mesh_assembly();
  ASSERT_TRUE(writer.WriteGltfSceneToFile(&model, path.string(), false, /*embedBuffers=*/false,
                                          true, false));
  ASSERT_TRUE(fs::exists(dir_ / "external.bin"));
  EXPECT_EQ(load_model(path.string(), {}).triangles.size(), 6u);
  fs::remove(dir_ / "external.bin");
  EXPECT_NE(error_of(path.string()).find("external.gltf"), std::string::npos);
}

TEST_F(MeshIo, GltfCompressedGeometryIsRefusedClearly) {
  tinygltf::Model model = two_mesh_assembly();
  model.extensionsUsed = model.extensionsRequired = {"KHR_draco_mesh_compression"};
  save(model, dir_ / "draco.gltf", false);
  EXPECT_NE(error_of((dir_ / "draco.gltf").string()).find("KHR_draco_mesh_compression"),
            std::string::npos);
}

TEST_F(MeshIo, GltfMirroringNodeKeepsTrianglesOutward) {
  tinygltf::Model model = two_mesh_assembly();
  model.nodes[0].scale = {-10, 10, 10};
  save(model, dir_ / "mirrored.gltf", false);
  ModelOptions right;
  right.mesh_name = "right";
  EXPECT_NEAR(signed_volume(load_model((dir_ / "mirrored.gltf").string(), right)), 1000.0 / 6,
              1e-3);
}

// ---- bad input -----------------------------------------------------------------------------

void expect_input_error(const std::string& spec, const std::string& fragment,
                        const ModelOptions& options = {}) {
  const std::string message = error_of(spec, options);
  EXPECT_FALSE(message.empty()) << spec << " loaded without error";
  EXPECT_NE(message.find(fragment), std::string::npos) << message;
  if (!spec.starts_with("builtin:")) {
    EXPECT_NE(message.find(spec), std::string::npos) << message;
  }
}

TEST_F(MeshIo, BadFilesAreInputErrorsNamingTheFile) {
  expect_input_error((dir_ / "missing.ply").string(), "not found");
  expect_input_error(dir_.string(), "not a regular file");
  expect_input_error(file("part.xyz", "x").string(), "unsupported model format");
  expect_input_error(file("bad_magic.ply", "plx\n").string(), "not a PLY file");
  expect_input_error(file("bad_format.ply", "ply\nformat foo 1.0\nend_header\n").string(),
                     "unknown format");
  expect_input_error(
      file("bad_type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty flot x\nend_header\n")
          .string(),
      "unknown property type");
  expect_input_error(file("no_end.ply", "ply\nformat ascii 1.0\nelement vertex 1\n").string(),
                     "end_header");
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  expect_input_error(file("no_faces.ply",
                          "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                          "property float y\nproperty float z\nend_header\n1 2 3\n")
                         .string(),
                     "no triangles");
  expect_input_error(file("nan.ply", header + "0 0 0\nnan 1 0\n0 1 0\n3 0 1 2\n").string(), "NaN");
  expect_input_error(file("inf.ply", header + "0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n").string(),
                     "infinite");
  expect_input_error(file("range.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n").string(),
                     "vertex 3");
  expect_input_error(file("negative.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n").string(),
                     "vertex index");
  expect_input_error(file("word.ply", header + "0 0 zero\n1 0 0\n0 1 0\n3 0 1 2\n").string(),
                     "bad number");
  expect_input_error(file("huge_count.ply",
                          "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n"
                          "property float x\nproperty float y\nproperty float z\nend_header\n")
                         .string(),
                     "truncated");
  expect_input_error(file("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n").string(),
                     "vertex 4");
  expect_input_error(file("empty.obj", "# nothing\n").string(), "no triangles");
  expect_input_error(file("empty.stl", "").string(), "not an STL");
  expect_input_error(file("empty.gltf", "").string(), "glTF");
  expect_input_error(file("garbage.gltf", "{ not json").string(), "glTF");
  expect_input_error(
      file("short.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0")
          .string(),
      "truncated");
}

TEST_F(MeshIo, BadOptionsAreInputErrors) {
  write_ply(dir_ / "bolt.ply", make_builtin_part("bolt"));
  const std::string spec = (dir_ / "bolt.ply").string();
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    ModelOptions scale;
    scale.unit_scale = bad;
    expect_input_error(spec, "unit scale", scale);
    ModelOptions diameter;
    diameter.diameter = bad;
    expect_input_error(spec, "diameter", diameter);
  }
  ModelOptions overflow;
  overflow.unit_scale = 1e300;
  expect_input_error(spec, "overflow", overflow);
  ModelOptions mesh_name;
  mesh_name.mesh_name = "part";
  expect_input_error(spec, "glTF", mesh_name);
  expect_input_error("builtin:sprocket", "bracket");
}

Mesh small_tetrahedron() {
  Mesh tetra;
  tetra.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tetra.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return tetra;
}

// Every prefix of a valid file (in memory: the readers are what is fuzzed) must be refused
// cleanly if the format is binary; a text file cut at the right place may still be complete,
// but nothing may crash.
TEST_F(MeshIo, TruncatedFilesNeverCrash) {
  for (const char* name : {"ply", "ply-ascii", "stl", "obj", "gltf", "glb"}) {
    SCOPED_TRACE(name);
    const MeshFormat format = mesh_format_named(name);
    const fs::path source = dir_ / (std::string("source_") + name + extension_of(format));
    write_mesh(source, small_tetrahedron(), format);
    const std::string bytes = read_file_bytes(source);
    const std::string extension = extension_of(format).substr(1);
    const bool binary =
        format == MeshFormat::ply || format == MeshFormat::stl || format == MeshFormat::glb;
    for (std::size_t length = 0; length < bytes.size(); ++length) {
      try {
        parse_model(std::string_view(bytes).substr(0, length), extension, {});
        EXPECT_FALSE(binary) << "cut at " << length << " of " << bytes.size() << " loaded";
      } catch (const InputError&) {
      }
    }
    // And once through a file, for the message naming it.
    const fs::path cut =
        file(std::string("cut") + extension_of(format), bytes.substr(0, bytes.size() / 2));
    EXPECT_NE(error_of(cut.string()).find(cut.string()), std::string::npos);
  }
}

TEST_F(MeshIo, RandomByteChangesNeverCrash) {
  std::mt19937 rng(1);
  for (const char* name : {"ply", "ply-ascii", "stl", "obj", "gltf", "glb"}) {
    const MeshFormat format = mesh_format_named(name);
    const fs::path source = dir_ / (std::string("source") + extension_of(format));
    write_mesh(source, small_tetrahedron(), format);
    const std::string bytes = read_file_bytes(source);
    const std::string extension = extension_of(format).substr(1);
    for (int trial = 0; trial < 2000; ++trial) {
      std::string corrupt = bytes;
      for (int k = 0; k < 3; ++k) corrupt[rng() % corrupt.size()] = static_cast<char>(rng());
      try {
        parse_model(corrupt, extension, {});
      } catch (const InputError&) {
      }
    }
  }
}

}  // namespace
}  // namespace binpick
