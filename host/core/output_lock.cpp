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

// NAME.shard-K-of-N.lock (K from 1).
std::string shard_lock_name(const std::string& name, int index, int count) {
  return name + ".shard-" + std::to_string(index + 1) + "-of-" + std::to_string(count) + ".lock";
}

// flock on lock_path (created), exclusive or shared; InputError naming `what` + output if another
// binpick holds it. An exclusive holder writes its pid into the file for that message.
int take_lock(const fs::path& lock_path, const fs::path& output, bool shared,
              const std::string& what) {
  const int fd = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0)
    throw InputError("cannot write " + output.string() + ": cannot create its lock file " +
                     lock_path.string() + ": " + std::strerror(errno));
  if (::flock(fd, (shared ? LOCK_SH : LOCK_EX) | LOCK_NB) != 0) {
    const int error = errno;
    const std::string pid = holder_pid(fd);
    ::close(fd);
    if (error == EWOULDBLOCK)
      throw InputError(what + output.string() + " is in use by another binpick (pid " + pid +
                       "): wait for it to end, or use another --out");
    throw InputError("cannot lock " + lock_path.string() + ": " + std::strerror(error));
  }
  // Best effort: the pid only makes the message of a refused run more useful (a full disk may
  // refuse even these few bytes; the lock holds regardless). Shared holders leave it alone.
  if (!shared) {
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(fd, 0) == 0) {
      [[maybe_unused]] const ssize_t ignored = ::pwrite(fd, pid.data(), pid.size(), 0);
    }
  }
  return fd;
}

}  // namespace

OutputLock OutputLock::directory(const fs::path& dir, int shard_index, int shard_count) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw InputError(dir.string() + " exists and is not a directory");
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir)) throw InputError("cannot create " + dir.string() + ": " + ec.message());
  if (shard_count > 1) {
    OutputLock lock(dir / ".binpick.lock", dir, true);
    lock.lock_shard(dir / shard_lock_name(".binpick", shard_index, shard_count), dir,
                    shard_index, shard_count);
    return lock;
  }
  OutputLock lock(dir / ".binpick.lock", dir);
  // Held: no other binpick writes here, so any temporary file is a killed writer's.
  remove_stale_temporaries(dir, true);
  return lock;
}

OutputLock OutputLock::file(const fs::path& file, int shard_index, int shard_count) {
  const fs::path dir = file.has_parent_path() ? file.parent_path() : fs::path(".");
  std::string name = ".";  // appended, not `"." + ...`: GCC 12 warns falsely (-Wrestrict)
  name += file.filename().string();
  if (shard_count > 1) {
    OutputLock lock(dir / (name + ".lock"), file, true);
    lock.lock_shard(dir / shard_lock_name(name, shard_index, shard_count), file, shard_index,
                    shard_count);
    return lock;
  }
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

OutputLock::OutputLock(const fs::path& lock_path, const fs::path& output, bool shared)
    : lock_path_(lock_path) {
  fd_ = take_lock(lock_path, output, shared, "");
}

void OutputLock::lock_shard(const fs::path& lock_path, const fs::path& output, int index,
                            int count) {
  shard_fd_ = take_lock(lock_path, output, false,
                        "shard " + std::to_string(index + 1) + "/" + std::to_string(count) + " of ");
}

OutputLock::OutputLock(OutputLock&& other) noexcept
    : lock_path_(std::move(other.lock_path_)), fd_(other.fd_), shard_fd_(other.shard_fd_) {
  other.fd_ = -1;
  other.shard_fd_ = -1;
}

OutputLock::~OutputLock() {
  // Closing the last descriptor releases the flock.
  if (shard_fd_ >= 0) ::close(shard_fd_);
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace binpick
