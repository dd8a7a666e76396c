#include "host/formats/mesh/ply_header.hpp"

#include <charconv>
#include <map>
#include <sstream>

#include "host/core/error.hpp"

namespace binpick::ply {
namespace {

Scalar scalar_named(const std::string& name) {
  static const std::map<std::string, Scalar> types = {
      {"char", Scalar::int8},      {"int8", Scalar::int8},       {"uchar", Scalar::uint8},
      {"uint8", Scalar::uint8},    {"short", Scalar::int16},     {"int16", Scalar::int16},
      {"ushort", Scalar::uint16},  {"uint16", Scalar::uint16},   {"int", Scalar::int32},
      {"int32", Scalar::int32},    {"uint", Scalar::uint32},     {"uint32", Scalar::uint32},
      {"float", Scalar::float32},  {"float32", Scalar::float32}, {"double", Scalar::float64},
      {"float64", Scalar::float64}};
  auto it = types.find(name);
  if (it == types.end()) throw InputError("PLY header: unknown property type '" + name + "'");
  return it->second;
}

std::vector<std::string> words_of(std::string_view line) {
  std::istringstream stream{std::string(line)};
  std::vector<std::string> words;
  for (std::string word; stream >> word;) words.push_back(word);
  return words;
}

}  // namespace

std::size_t size_of(Scalar type) {
  switch (type) {
    case Scalar::int8:
    case Scalar::uint8:
      return 1;
    case Scalar::int16:
    case Scalar::uint16:
      return 2;
    case Scalar::int32:
    case Scalar::uint32:
    case Scalar::float32:
      return 4;
    case Scalar::float64:
      return 8;
  }
  return 0;
}

Header parse_header(std::string_view bytes) {
  if (!bytes.starts_with("ply\n") && !bytes.starts_with("ply\r\n"))
    throw InputError("not a PLY file (it does not start with 'ply')");
  Header header;
  bool has_format = false;
  std::size_t position = bytes.find('\n') + 1;
  while (true) {
    const std::size_t end = bytes.find('\n', position);
    if (end == std::string_view::npos) throw InputError("PLY header: no end_header line");
    const auto words = words_of(bytes.substr(position, end - position));
    position = end + 1;
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    const std::string& keyword = words[0];
    if (keyword == "end_header") break;
    if (keyword == "format") {
      if (words.size() != 3) throw InputError("PLY header: malformed format line");
      if (words[1] == "ascii") {
        header.encoding = Encoding::ascii;
      } else if (words[1] == "binary_little_endian") {
        header.encoding = Encoding::binary_little_endian;
      } else if (words[1] == "binary_big_endian") {
        header.encoding = Encoding::binary_big_endian;
      } else {
        throw InputError("PLY header: unknown format '" + words[1] + "'");
      }
      has_format = true;
    } else if (keyword == "element") {
      Element element;
      if (words.size() != 3) throw InputError("PLY header: malformed element line");
      element.name = words[1];
      const auto& count = words[2];
      auto [ptr, ec] = std::from_chars(count.data(), count.data() + count.size(), element.count);
      if (ec != std::errc{} || ptr != count.data() + count.size())
        throw InputError("PLY header: bad element count '" + count + "'");
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty()) throw InputError("PLY header: property before any element");
      Property property;
      if (words.size() == 5 && words[1] == "list") {
        property.is_list = true;
        property.count_type = scalar_named(words[2]);
        if (property.count_type == Scalar::float32 || property.count_type == Scalar::float64)
          throw InputError("PLY header: list length type must be an integer type");
        property.type = scalar_named(words[3]);
        property.name = words[4];
      } else if (words.size() == 3) {
        property.type = scalar_named(words[1]);
        property.name = words[2];
      } else {
        throw InputError("PLY header: malformed property line");
      }
      header.elements.back().properties.push_back(std::move(property));
    } else {
      throw InputError("PLY header: unknown line '" + keyword + "'");
    }
  }
  if (!has_format) throw InputError("PLY header: no format line");
  header.body_offset = position;
  return header;
}

}  // namespace binpick::ply
