#include "runtime/output/disk_reservation.h"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "common/base/error.h"

namespace ffriga {

namespace {

std::string mib(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
  return text;
}

}  // namespace

std::uint64_t DiskReservation::fileSize() const {
  struct stat st;
  if (::fstat(fd_, &st) != 0) return 0;
  return static_cast<std::uint64_t>(st.st_size);
}

void DiskReservation::ensure(std::uint64_t end) {
  if (end <= reserved_) return;
  struct rlimit limit;
  if (::getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY &&
      end > static_cast<std::uint64_t>(limit.rlim_cur)) {
    throw ComputeError(Str() << path_ << ": file size limit reached (ulimit -f: "
                             << mib(limit.rlim_cur) << "); the next rows need the file to grow to "
                             << mib(end) << "; the file holds the rows of the last flush");
  }
  const std::uint64_t size = fileSize();
  if (end <= size) {
    reserved_ = end;
    return;
  }
  if (::fallocate(fd_, FALLOC_FL_KEEP_SIZE, static_cast<off_t>(size),
                  static_cast<off_t>(end - size)) == 0) {
    reserved_ = end;
    return;
  }
  const int err = errno;
  if (err == EOPNOTSUPP || err == ENOSYS) {  // no fallocate: at least the free space
    struct statvfs fs;
    if (::fstatvfs(fd_, &fs) == 0 &&
        static_cast<std::uint64_t>(fs.f_bavail) * fs.f_frsize < end - size) {
      throw ComputeError(Str() << path_ << ": disk full (" << mib(static_cast<std::uint64_t>(
                                                                  fs.f_bavail) * fs.f_frsize)
                               << " free, the next rows need up to " << mib(end - size)
                               << "); the file holds the rows of the last flush");
    }
    return;
  }
  throw ComputeError(Str() << path_ << ": "
                           << (err == ENOSPC ? std::string("disk full")
                               : err == EFBIG ? std::string("file too large")
                                              : std::string(std::strerror(err)))
                           << ": cannot reserve " << mib(end - size)
                           << " for the next rows; the file holds the rows of the last flush");
}

void DiskReservation::release() {
  const std::uint64_t size = fileSize();
  if (reserved_ > size) {
    ::fallocate(fd_, FALLOC_FL_PUNCH_HOLE | FALLOC_FL_KEEP_SIZE, static_cast<off_t>(size),
                static_cast<off_t>(reserved_ - size));
  }
  reserved_ = 0;
}

}  // namespace ffriga
