#include "runtime/output/writer_lock.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "common/base/error.h"

namespace ffriga {

namespace {

// The locked byte: far beyond the end of any result file (HDF5 never writes there).
constexpr off_t kLockOffset = off_t{1} << 62;

struct flock lockRequest(short type) {
  struct flock l;
  std::memset(&l, 0, sizeof l);
  l.l_type = type;
  l.l_whence = SEEK_SET;
  l.l_start = kLockOffset;
  l.l_len = 1;
  return l;
}

[[noreturn]] void throwBeingWritten(const std::string& path, long other) {
  const std::string who = other > 0 ? std::string(Str() << " (process " << other << ")") : "";
  throw InputError(Str() << path << ": the result file is being written by another ffrsim" << who
                         << "; wait for it to end or stop it first");
}

}  // namespace

WriterLock::WriterLock(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd_ < 0) {
    throw InputError(Str() << path << ": cannot open the result file for writing ("
                           << std::strerror(errno) << ")");
  }
  try {
    acquire();
  } catch (...) {
    ::close(fd_);  // the destructor does not run for an object never constructed
    throw;
  }
}

WriterLock::~WriterLock() {
  if (fd_ >= 0) ::close(fd_);
}

void WriterLock::acquire() {
  struct flock l = lockRequest(F_WRLCK);
  if (::fcntl(fd_, F_SETLK, &l) == 0) return;
  const int err = errno;
  if (err == EACCES || err == EAGAIN) throwBeingWritten(path_, holder(path_));
  // File systems without record locks (ENOLCK, EINVAL): the file is written unguarded.
}

void WriterLock::refuseIfHeld(const std::string& path) {
  const long other = holder(path);
  if (other > 0 && other != static_cast<long>(::getpid())) throwBeingWritten(path, other);
}

long WriterLock::holder(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0;
  struct flock l = lockRequest(F_WRLCK);
  const bool asked = ::fcntl(fd, F_GETLK, &l) == 0;
  ::close(fd);
  return asked && l.l_type != F_UNLCK ? static_cast<long>(l.l_pid) : 0;
}

}  // namespace ffriga
