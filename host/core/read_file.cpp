#include "host/core/read_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

#include "host/core/error.hpp"

namespace binpick {

void require_regular_file(const std::filesystem::path& path) {
  std::error_code ec;
  auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw InputError(path.string() + ": file not found");
  if (!std::filesystem::is_regular_file(status))
    throw InputError(path.string() + ": not a regular file");
}

std::string read_file_bytes(const std::filesystem::path& path) {
  require_regular_file(path);
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw InputError(path.string() + ": cannot open: " + std::strerror(errno));
  std::string bytes{std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
  if (stream.bad()) throw InputError(path.string() + ": read error");
  return bytes;
}

}  // namespace binpick
