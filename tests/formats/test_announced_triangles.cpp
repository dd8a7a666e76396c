// A model's triangle count read from its header (announced_triangles.hpp) agrees with what the
// readers find, and a model over kMaxModelTriangles is refused before its geometry is parsed.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <unistd.h>

#include "host/core/error.hpp"
#include "host/core/read_file.hpp"
#include "host/formats/mesh/announced_triangles.hpp"
#include "host/formats/mesh/little_endian.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "host/formats/mesh/mesh_writers.hpp"
#include "synth/parts/builtin_parts.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;

std::string refusal(std::string_view bytes, std::string_view format) {
  try {
    parse_model(bytes, format, {});
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(AnnouncedTriangles, EqualsTheTrianglesTheReadersFindInEveryFormat) {
  const fs::path dir = fs::temp_directory_path() / ("binpick_announced_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const char* part_name : {"bracket", "tee"}) {
    const Mesh part = make_builtin_part(part_name);
    for (const char* name : {"ply", "ply-ascii", "stl", "obj", "gltf", "glb"}) {
      SCOPED_TRACE(std::string(part_name) + " " + name);
      const MeshFormat format = mesh_format_named(name);
      const fs::path path = dir / (std::string("part") + extension_of(format));
      write_mesh(path, part, format);
      const std::string kind = extension_of(format).substr(1);
      EXPECT_EQ(announced_triangles(read_file_bytes(path), kind), part.triangles.size());
    }
  }
  fs::remove_all(dir);
}

TEST(AnnouncedTriangles, CountsTheRecordsOfFormatsWithoutAHeader) {
  EXPECT_EQ(announced_triangles("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\n  f 2 4 3\n"
                                "# f 1 2 3\nfoo\n",
                                "obj"),
            2u);
  const std::string facet =
      "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n"
      " endloop\nendfacet\n";
  EXPECT_EQ(announced_triangles("solid x\n" + facet + "  " + facet + "endsolid x\n", "stl"), 2u);
}

TEST(AnnouncedTriangles, UnreadableHeadersAnnounceNothing) {
  for (const char* format : {"ply", "stl", "obj", "gltf", "glb"}) {
    SCOPED_TRACE(format);
    EXPECT_EQ(announced_triangles("", format), 0u);
    EXPECT_EQ(announced_triangles("\x01\x02garbage{", format), 0u);
  }
  EXPECT_EQ(announced_triangles("glTF\x02\0\0\0", "glb"), 0u);
  EXPECT_EQ(announced_triangles(R"({"meshes": 3, "accessors": {}})", "gltf"), 0u);
}

// A PLY and a glTF header claim more triangles than binpick reads, over a body that holds none: the
// refusal names the count, so it came from the header, not from a truncated body.
TEST(AnnouncedTriangles, AnOverLargeModelIsRefusedFromItsHeader) {
  const std::uint64_t too_many = kMaxModelTriangles + 1;
  const std::string count = std::to_string(too_many);
  const std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
                          "property float x\nproperty float y\nproperty float z\n"
                          "element face " + count + "\nproperty list uchar int vertex_indices\n"
                          "end_header\n";
  EXPECT_NE(refusal(ply, "ply").find(count + " triangles"), std::string::npos) << refusal(ply, "ply");

  // (A binary STL announces its count only when the file's size matches it, 50 bytes a
  // triangle: 1 GB here, so the parity test above covers it.)
  const std::string gltf = R"({"asset": {"version": "2.0"}, "accessors": [{"count": )" +
                           std::to_string(3 * too_many) +
                           R"(, "componentType": 5125, "type": "SCALAR"}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 0}]}]})";
  EXPECT_NE(refusal(gltf, "gltf").find(count + " triangles"), std::string::npos)
      << refusal(gltf, "gltf");
}

}  // namespace
}  // namespace binpick
