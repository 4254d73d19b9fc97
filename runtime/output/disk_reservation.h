// Space on disk reserved ahead of a result file's writes, so that a full disk or a file size
// limit stops a run between two flushes instead of in the middle of one. HDF5 updates a
// file in place: a flush that fails half-way (ENOSPC, EFBIG) leaves metadata on disk that
// points at blocks never written, and the file no longer opens. Before each flush the
// result file asks for the bytes the flush can add (runtime/output/result_file.h); they are
// allocated with fallocate(FALLOC_FL_KEEP_SIZE), which changes no byte and not the file's
// size, and checked against the file size limit (ulimit -f). If either says no, nothing of
// the flush is written: the file stays as the last flush left it, readable, and small
// writes (the final status, the close) still fit in what was reserved before.
//
// File systems without fallocate (some network file systems) get a check of their free
// space instead: a limit, not a guarantee.
#pragma once

#include <cstdint>
#include <string>

namespace ffriga {

class DiskReservation {
 public:
  // `descriptor`: a descriptor of the file open for writing, owned by the caller.
  DiskReservation(const std::string& path, int descriptor) : path_(path), fd_(descriptor) {}

  // Ensures that the file can grow to `end` bytes. ComputeError naming the file, the limit
  // and the bytes asked for if not (then nothing was reserved, and nothing changed).
  void ensure(std::uint64_t end);
  // The file's size on disk now (bytes).
  std::uint64_t fileSize() const;
  // Returns the reserved blocks beyond the file's end to the file system (at close).
  void release();

 private:
  std::string path_;
  int fd_ = -1;
  std::uint64_t reserved_ = 0;  // the file can grow to this many bytes without a failure
};

}  // namespace ffriga
