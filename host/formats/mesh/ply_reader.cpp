// PLY body reading: vertices (x y z, optional nx ny nz), faces (a list of vertex indices, fan-
// triangulated); every other element and property is read past and ignored.
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <optional>

#include "host/core/error.hpp"
#include "host/formats/mesh/mesh_readers.hpp"
#include "host/formats/mesh/ply_header.hpp"

namespace binpick {
namespace {

// Yields the body's values one by one, as doubles (exact for every PLY integer type).
class BodyReader {
 public:
  BodyReader(std::string_view body, ply::Encoding encoding) : body_(body), encoding_(encoding) {}

  double read(ply::Scalar type) {
    return encoding_ == ply::Encoding::ascii ? read_ascii() : read_binary(type);
  }

  std::size_t remaining_bytes() const { return body_.size() - position_; }

 private:
  double read_ascii() {
    auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
    while (position_ < body_.size() && is_space(body_[position_])) ++position_;
    std::size_t end = position_;
    while (end < body_.size() && !is_space(body_[end])) ++end;
    if (end == position_) throw InputError("PLY body is truncated");
    const char* first = body_.data() + position_;
    const char* last = body_.data() + end;
    if (*first == '+') ++first;  // from_chars does not accept a leading '+'
    double value = 0;
    auto [ptr, ec] = std::from_chars(first, last, value);
    if (ec != std::errc{} || ptr != last)
      throw InputError("PLY body: bad number '" + std::string(body_.data() + position_, last) +
                       "'");
    position_ = end;
    return value;
  }

  template <typename T>
  T load() {
    T value;
    std::memcpy(&value, body_.data() + position_, sizeof(T));
    const bool file_is_little = encoding_ == ply::Encoding::binary_little_endian;
    if (file_is_little != (std::endian::native == std::endian::little)) {
      auto* bytes = reinterpret_cast<unsigned char*>(&value);
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
    }
    position_ += sizeof(T);
    return value;
  }

  double read_binary(ply::Scalar type) {
    if (remaining_bytes() < ply::size_of(type)) throw InputError("PLY body is truncated");
    switch (type) {
      case ply::Scalar::int8:
        return load<std::int8_t>();
      case ply::Scalar::uint8:
        return load<std::uint8_t>();
      case ply::Scalar::int16:
        return load<std::int16_t>();
      case ply::Scalar::uint16:
        return load<std::uint16_t>();
      case ply::Scalar::int32:
        return load<std::int32_t>();
      case ply::Scalar::uint32:
        return load<std::uint32_t>();
      case ply::Scalar::float32:
        return load<float>();
      case ply::Scalar::float64:
        return load<double>();
    }
    return 0;
  }

  std::string_view body_;
  ply::Encoding encoding_;
  std::size_t position_ = 0;
};

std::uint64_t read_count_or_index(BodyReader& reader, ply::Scalar type, const char* what) {
  const double value = reader.read(type);
  if (!(value >= 0 && value <= 4294967295.0) || value != std::floor(value))
    throw InputError(std::string("PLY body: bad ") + what + " " + std::to_string(value));
  return static_cast<std::uint64_t>(value);
}

// Refuses element counts the remaining bytes cannot hold, before anything is allocated.
void check_count_fits(const ply::Element& element, const BodyReader& reader,
                      ply::Encoding encoding) {
  std::size_t min_bytes = 0;
  for (const auto& p : element.properties) {
    // An ascii value takes at least a digit and a separator (but the file's last value may
    // lack its separator, hence the + 1 below).
    min_bytes +=
        encoding == ply::Encoding::ascii ? 2 : ply::size_of(p.is_list ? p.count_type : p.type);
  }
  if (min_bytes > 0 && element.count > (reader.remaining_bytes() + 1) / min_bytes)
    throw InputError("PLY body is truncated: " + std::to_string(element.count) + " " +
                     element.name + " elements do not fit in the file");
}

std::optional<std::size_t> property_index(const ply::Element& element, const std::string& name) {
  for (std::size_t i = 0; i < element.properties.size(); ++i) {
    if (element.properties[i].name == name && !element.properties[i].is_list) return i;
  }
  return std::nullopt;
}

std::optional<std::size_t> face_list_index(const ply::Element& element) {
  std::optional<std::size_t> any_list;
  for (std::size_t i = 0; i < element.properties.size(); ++i) {
    const auto& p = element.properties[i];
    if (!p.is_list) continue;
    if (p.name == "vertex_indices" || p.name == "vertex_index") return i;
    if (!any_list) any_list = i;
  }
  return any_list;
}

void read_vertices(const ply::Element& element, BodyReader& reader, Mesh& mesh) {
  const auto x = property_index(element, "x"), y = property_index(element, "y"),
             z = property_index(element, "z");
  if (!x || !y || !z) throw InputError("PLY vertex element has no x, y and z properties");
  const auto nx = property_index(element, "nx"), ny = property_index(element, "ny"),
             nz = property_index(element, "nz");
  const bool has_normals = nx && ny && nz;
  mesh.positions.reserve(element.count);
  if (has_normals) mesh.normals.reserve(element.count);
  std::vector<double> values(element.properties.size());
  for (std::uint64_t i = 0; i < element.count; ++i) {
    for (std::size_t k = 0; k < element.properties.size(); ++k) {
      const auto& p = element.properties[k];
      if (p.is_list) {
        const auto n = read_count_or_index(reader, p.count_type, "list length");
        for (std::uint64_t j = 0; j < n; ++j) reader.read(p.type);
      } else {
        values[k] = reader.read(p.type);
      }
    }
    mesh.positions.emplace_back(values[*x], values[*y], values[*z]);
    if (has_normals) mesh.normals.emplace_back(values[*nx], values[*ny], values[*nz]);
  }
}

void read_faces(const ply::Element& element, BodyReader& reader, Mesh& mesh) {
  const auto indices = face_list_index(element);
  if (!indices) throw InputError("PLY face element has no vertex_indices list");
  mesh.triangles.reserve(element.count);
  std::vector<std::uint32_t> polygon;
  for (std::uint64_t i = 0; i < element.count; ++i) {
    for (std::size_t k = 0; k < element.properties.size(); ++k) {
      const auto& p = element.properties[k];
      if (!p.is_list) {
        reader.read(p.type);
        continue;
      }
      const auto n = read_count_or_index(reader, p.count_type, "list length");
      polygon.clear();
      for (std::uint64_t j = 0; j < n; ++j) {
        if (k == *indices) {
          polygon.push_back(
              static_cast<std::uint32_t>(read_count_or_index(reader, p.type, "vertex index")));
        } else {
          reader.read(p.type);
        }
      }
      // Fan triangulation: exact for the convex polygons PLY files hold in practice.
      for (std::size_t j = 1; j + 1 < polygon.size(); ++j) {
        mesh.triangles.push_back({polygon[0], polygon[j], polygon[j + 1]});
      }
    }
  }
}

}  // namespace

Mesh read_ply(std::string_view bytes) {
  const ply::Header header = ply::parse_header(bytes);
  BodyReader reader(bytes.substr(header.body_offset), header.encoding);
  Mesh mesh;
  bool has_vertices = false;
  for (const auto& element : header.elements) {
    check_count_fits(element, reader, header.encoding);
    if (element.name == "vertex") {
      read_vertices(element, reader, mesh);
      has_vertices = true;
    } else if (element.name == "face") {
      read_faces(element, reader, mesh);
    } else if (!element.properties.empty()) {  // without properties it takes no bytes
      for (std::uint64_t i = 0; i < element.count; ++i) {
        for (const auto& p : element.properties) {
          const auto n = p.is_list ? read_count_or_index(reader, p.count_type, "list length") : 1;
          for (std::uint64_t j = 0; j < n; ++j) reader.read(p.type);
        }
      }
    }
  }
  if (!has_vertices) throw InputError("PLY file has no vertex element");
  return mesh;
}

}  // namespace binpick
