#include "host/app/output_file.hpp"

#include "host/core/error.hpp"

namespace binpick::cli {

void check_output_file(const std::filesystem::path& out) {
  namespace fs = std::filesystem;
  const auto dir = out.has_parent_path() ? out.parent_path() : fs::path(".");
  if (!fs::is_directory(dir))
    throw InputError("--out " + out.string() + ": directory " + dir.string() + " does not exist");
  if (fs::is_directory(out)) throw InputError("--out " + out.string() + " is a directory");
}

}  // namespace binpick::cli
