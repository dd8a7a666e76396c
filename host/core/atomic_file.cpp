#include "host/core/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <regex>
#include <string>
#include <system_error>
#include <vector>

#include "host/core/error.hpp"

namespace binpick {
namespace {

// Unique within the process (counter) and across processes (pid), so concurrent writers of the
// same target never share a temporary file.
std::filesystem::path temporary_path_for(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  std::string name = ".";
  name += path.filename().string();
  name += ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  return path.parent_path() / name;
}

// Why a write failed: the stream keeps no reason, the failing write(2) left it in errno
// (ENOSPC on a full disk, EDQUOT, EIO).
std::string write_error() {
  return errno ? std::strerror(errno) : "write failed (disk full?)";
}

// Removes the temporary file unless the rename succeeded.
class TemporaryFile {
 public:
  explicit TemporaryFile(std::filesystem::path path) : path_(std::move(path)) {}
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  ~TemporaryFile() {
    if (!committed_) {
      std::error_code ignored;
      std::filesystem::remove(path_, ignored);
    }
  }
  const std::filesystem::path& path() const { return path_; }
  void commit_as(const std::filesystem::path& target) {
    std::error_code ec;
    std::filesystem::rename(path_, target, ec);
    if (ec) throw InputError("cannot write " + target.string() + ": " + ec.message());
    committed_ = true;
  }

 private:
  std::filesystem::path path_;
  bool committed_ = false;
};

// The names temporary_path_for and the plots' writer (host/eval/report/gnuplot.cpp) give.
bool is_temporary_name(const std::string& name) {
  static const std::regex pattern(R"(^\..+\.(tmp[0-9]+_[0-9]+|[0-9]+\.partial)$)");
  return std::regex_match(name, pattern);
}

}  // namespace

std::size_t remove_stale_temporaries(const std::filesystem::path& dir, bool recursive,
                                     const std::string& name_prefix) {
  namespace fs = std::filesystem;
  std::vector<fs::path> stale;
  std::error_code ec;
  const auto consider = [&](const fs::directory_entry& entry) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with(name_prefix) && is_temporary_name(name) && entry.is_regular_file(ec))
      stale.push_back(entry.path());
  };
  if (recursive) {
    for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
      consider(*it);
  } else {
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
      consider(*it);
  }
  std::size_t removed = 0;
  for (const fs::path& path : stale) removed += fs::remove(path, ec) ? 1 : 0;
  return removed;
}

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write) {
  if (path.filename().empty())
    throw InputError("cannot write '" + path.string() + "': not a file name");
  if (std::filesystem::is_directory(path))
    throw InputError("cannot write " + path.string() + ": it is a directory");
  TemporaryFile temporary(temporary_path_for(path));
  {
    std::ofstream stream(temporary.path(), std::ios::binary | std::ios::trunc);
    if (!stream) {
      throw InputError("cannot write " + path.string() + ": " + std::strerror(errno));
    }
    errno = 0;
    write(stream);
    stream.flush();
    if (!stream) throw InputError("cannot write " + path.string() + ": " + write_error());
    stream.close();
    if (!stream) throw InputError("cannot write " + path.string() + ": " + write_error());
  }
  temporary.commit_as(path);
}

}  // namespace binpick
