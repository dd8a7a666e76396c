// One binpick at a time per output: a verb that writes an output directory or file holds an
// OutputLock on it for its whole run, so a second binpick started on the same output is
// refused instead of interleaving its files with the first's. The lock is flock(2) on a small
// file beside (or in) the output: the kernel releases it when the process ends in any way,
// SIGKILL included, so an interrupted run never leaves a stale lock and the same command
// resumes at once.
#pragma once

#include <filesystem>

namespace binpick {

class OutputLock {
 public:
  // Locks directory `dir` (created if missing) through DIR/.binpick.lock. Throws InputError
  // "DIR is in use by another binpick (pid N)" if another process holds it, or if the lock
  // file cannot be made (naming the reason: read-only, no space, ...).
  static OutputLock directory(const std::filesystem::path& dir);
  // Locks output file `file` through .NAME.lock in its directory (which must exist). The
  // same errors, naming the file.
  static OutputLock file(const std::filesystem::path& file);

  OutputLock(OutputLock&& other) noexcept;
  OutputLock& operator=(OutputLock&&) = delete;
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  ~OutputLock();  // unlocks (the lock file stays: removing it would race with a new locker)

  const std::filesystem::path& lock_path() const { return lock_path_; }

 private:
  OutputLock(const std::filesystem::path& lock_path, const std::filesystem::path& output);
  std::filesystem::path lock_path_;
  int fd_ = -1;
};

}  // namespace binpick
