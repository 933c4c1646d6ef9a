// An exclusive lock on a file, for a folder one process at a time may write
// (mrsim-opt's run folder): a second writer is told which process holds it
// instead of both overwriting the same files.
#pragma once

#include <stdexcept>
#include <string>

namespace mrsim {

// Thrown when another live process holds the lock.
class FileLockBusy : public std::runtime_error {
 public:
  FileLockBusy(const std::string& what, long holder)
      : std::runtime_error(what), holder_(holder) {}
  // The holder's process id as it wrote it (0 when unreadable).
  long holder() const { return holder_; }

 private:
  long holder_;
};

// Holds flock(LOCK_EX) on `path` (created if missing) for its lifetime and
// writes this process's id into it. The kernel drops the lock when the
// holder exits however it exits, so a lock file left by a killed run is
// stale and simply taken over (stale_holder() says whose it was). The file
// is emptied, not removed, on release: removing it would let two
// processes lock two different files of the same name.
class FileLock {
 public:
  // Throws FileLockBusy naming the holder's pid, or std::runtime_error
  // when the file cannot be opened.
  explicit FileLock(std::string path);
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

  const std::string& path() const { return path_; }
  // The pid a run that ended without releasing left in the file, 0 when
  // the file was empty (free).
  long stale_holder() const { return stale_holder_; }

 private:
  std::string path_;
  int fd_ = -1;
  long stale_holder_ = 0;
};

}  // namespace mrsim
