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
  //
  // Shards (--shard K/N, shard_count > 1) of one batch write one output at once by design: each
  // holds the lock shared (so an unsharded run is refused while any shard runs, and a shard
  // while an unsharded run does) and DIR/.binpick.shard-K-of-N.lock exclusively (the same shard
  // twice is refused). A shard leaves other writers' temporaries alone: they may be a running
  // shard's; the unsharded run or the next exclusive lock removes those of killed writers.
  static OutputLock directory(const std::filesystem::path& dir, int shard_index = 0,
                              int shard_count = 1);
  // Locks output file `file` through .NAME.lock in its directory (which must exist). The
  // same errors, naming the file; shards as above (.NAME.shard-K-of-N.lock).
  static OutputLock file(const std::filesystem::path& file, int shard_index = 0,
                         int shard_count = 1);

  OutputLock(OutputLock&& other) noexcept;
  OutputLock& operator=(OutputLock&&) = delete;
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  ~OutputLock();  // unlocks (the lock file stays: removing it would race with a new locker)

  const std::filesystem::path& lock_path() const { return lock_path_; }

 private:
  // shared: flock LOCK_SH (a shard's hold on the whole output) instead of LOCK_EX.
  OutputLock(const std::filesystem::path& lock_path, const std::filesystem::path& output,
             bool shared = false);
  std::filesystem::path lock_path_;
  void lock_shard(const std::filesystem::path& lock_path, const std::filesystem::path& output,
                  int index, int count);
  int fd_ = -1;
  int shard_fd_ = -1;  // a shard's own exclusive lock
};

}  // namespace binpick
