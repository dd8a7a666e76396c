// The checks of an --out file that a verb writes in one piece (train's model, detect's results),
// made before any slow work so that a typo fails at once.
#pragma once

#include <filesystem>

namespace binpick::cli {

// InputError naming --out if its directory does not exist or it is itself a directory.
void check_output_file(const std::filesystem::path& out);

}  // namespace binpick::cli
