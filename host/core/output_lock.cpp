#include "host/core/output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

#include "host/core/atomic_file.hpp"
#include "host/core/error.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;

// The pid the holder wrote into the lock file, or "unknown" (it may not have written it yet).
std::string holder_pid(int fd) {
  char text[32] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::string pid(text, n > 0 ? std::size_t(n) : 0);
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  return pid.empty() ? "unknown" : pid;
}

}  // namespace

OutputLock OutputLock::directory(const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw InputError(dir.string() + " exists and is not a directory");
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir)) throw InputError("cannot create " + dir.string() + ": " + ec.message());
  OutputLock lock(dir / ".binpick.lock", dir);
  // Held: no other binpick writes here, so any temporary file is a killed writer's.
  remove_stale_temporaries(dir, true);
  return lock;
}

OutputLock OutputLock::file(const fs::path& file) {
  const fs::path dir = file.has_parent_path() ? file.parent_path() : fs::path(".");
  std::string name = ".";  // appended, not `"." + ...`: GCC 12 warns falsely (-Wrestrict)
  name += file.filename().string();
  name += ".lock";
  OutputLock lock(dir / name, file);
  // The killed writers' temporaries of this output and of its siblings (detect's
  // NAME.details.csv beside NAME.csv, its NAME.csv.parts/), not those of other outputs.
  std::string prefix = ".";
  prefix += file.stem().string();
  remove_stale_temporaries(dir, false, prefix);
  remove_stale_temporaries(fs::path(file.string() + ".parts"), true);
  return lock;
}

OutputLock::OutputLock(const fs::path& lock_path, const fs::path& output) : lock_path_(lock_path) {
  fd_ = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw InputError("cannot write " + output.string() + ": cannot create its lock file " +
                     lock_path.string() + ": " + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    const std::string pid = holder_pid(fd_);
    ::close(fd_);
    if (error == EWOULDBLOCK)
      throw InputError(output.string() + " is in use by another binpick (pid " + pid +
                       "): wait for it to end, or use another --out");
    throw InputError("cannot lock " + lock_path.string() + ": " + std::strerror(error));
  }
  // Best effort: the pid only makes the message of a refused run more useful (a full disk may
  // refuse even these few bytes; the lock holds regardless).
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) == 0) {
    [[maybe_unused]] const ssize_t ignored = ::pwrite(fd_, pid.data(), pid.size(), 0);
  }
}

OutputLock::OutputLock(OutputLock&& other) noexcept
    : lock_path_(std::move(other.lock_path_)), fd_(other.fd_) {
  other.fd_ = -1;
}

OutputLock::~OutputLock() {
  if (fd_ >= 0) ::close(fd_);  // closing the last descriptor releases the flock
}

}  // namespace binpick
