// One writer per result file. In SWMR mode HDF5 gives up its own file lock (so that readers
// can open the file while it grows), and a result file that was killed while being written
// keeps HDF5's "open for writing" mark; neither tells whether another ffrsim still writes
// the file. The writer lock does: a POSIX record lock (fcntl) on one byte far beyond any
// file's end, held while the file is open for writing and gone with the process, however it
// ends (also SIGKILL). HDF5's own locks are flock()s, which are independent of record locks
// on Linux's local file systems, so readers are not affected.
//
// POSIX semantics: closing any descriptor of the file in this process drops the lock; the
// result file re-takes it after it closed and reopened the file (acquire() again).
#pragma once

#include <string>

namespace ffriga {

class WriterLock {
 public:
  // Takes the lock on `path` (created if missing). InputError naming the file and the other
  // process if another process holds it.
  explicit WriterLock(const std::string& path);
  ~WriterLock();
  WriterLock(const WriterLock&) = delete;
  WriterLock& operator=(const WriterLock&) = delete;

  // Takes the lock again (after a descriptor of the file was closed in this process).
  void acquire();
  // The descriptor the lock is held through (open for reading and writing).
  int descriptor() const { return fd_; }

  // The process that holds a writer lock on `path`, or 0 if none does (or the file is
  // missing).
  static long holder(const std::string& path);
  // InputError "being written by another ffrsim" if another process holds the lock on
  // `path` (checked before reading a file that may still be written, e.g. for --restart).
  static void refuseIfHeld(const std::string& path);

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace ffriga
