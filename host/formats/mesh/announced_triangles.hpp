// How many triangles a model file holds, told from its header (PLY's face count, binary STL's
// triangle count, glTF's accessors) or, for formats without one (OBJ, ascii STL), from a scan
// for face records, without parsing the geometry: load_model refuses a model over
// kMaxModelTriangles at once instead of after reading it.
#pragma once

#include <cstdint>
#include <string_view>

namespace binpick {

// A part's CAD export or scan rarely has a million triangles; training re-meshes it to a few
// thousand points anyway. Beyond this a model is refused with advice to decimate it.
inline constexpr std::uint64_t kMaxModelTriangles = 20'000'000;

// A lower bound on the triangles of a model file in format ("ply", "stl", "obj", "gltf", "glb";
// a polygon counts once), or 0 where the header cannot be read (the reader reports that).
std::uint64_t announced_triangles(std::string_view bytes, std::string_view format);

}  // namespace binpick
