// The header of a PLY file: its encoding and the elements with their typed properties.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace binpick::ply {

enum class Encoding { ascii, binary_little_endian, binary_big_endian };

enum class Scalar { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

std::size_t size_of(Scalar type);

struct Property {
  std::string name;
  Scalar type = Scalar::float32;  // of the value, or of each list item
  bool is_list = false;
  Scalar count_type = Scalar::uint8;  // of the list length
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

struct Header {
  Encoding encoding = Encoding::ascii;
  std::vector<Element> elements;
  std::size_t body_offset = 0;  // first byte after the end_header line
};

// Parses the header at the start of bytes; throws binpick::InputError on a malformed header.
Header parse_header(std::string_view bytes);

}  // namespace binpick::ply
