// Reading a whole input file, with the errors a user can act on.
#pragma once

#include <filesystem>
#include <string>

namespace binpick {

// The bytes of path. Throws binpick::InputError naming path if it does not exist, is not a
// regular file or cannot be read.
std::string read_file_bytes(const std::filesystem::path& path);

// Throws binpick::InputError naming path unless it is an existing regular file.
void require_regular_file(const std::filesystem::path& path);

}  // namespace binpick
