// The HDF5 result file of ffrsim (layout, units and version: schemas/result_format.md) as
// the outputs write it: its root and group attributes, and series, chunked datasets with an
// unlimited first dimension that grow by one row per output time.
//
// Rows are kept in memory and written as one block per series at writeRows() (one HDF5
// extent and write per series instead of one per row); flushFile() then flushes the HDF5
// file. Opened for a restart (`appending`), the groups and series exist already: they are
// opened and checked for their shape instead of created, and every series is cut back to the
// rows of the restart record.
//
// A file goes through three phases:
//   building  every group, dataset and attribute the run will write is created;
//   SWMR      (startSwmr) HDF5's single-writer/multiple-reader mode: readers open the file
//             with SWMR (h5py.File(path, "r", swmr=True)) while it grows and see every
//             flushed row. Only appends and in-place writes are allowed then: attributes set
//             in this phase (status, the run's figures) are kept and written at close;
//   closing   (close) the SWMR file is closed, reopened normally for those attributes and
//             closed again: a completed, interrupted or failed run's file opens anywhere.
// A run killed in the SWMR phase leaves HDF5's "open for writing" mark: SWMR readers open it,
// `ffrsim --restart` clears the mark (under the writer lock, runtime/output/writer_lock.h),
// other readers after `h5clear -s RESULT.h5`.
//
// Writes that fail: before each flush the bytes it can add are reserved on disk
// (reserve(), runtime/output/disk_reservation.h); a refusal leaves the file as the last
// flush left it. A write that fails anyway (an I/O error) marks the file broken: nothing is
// written or closed any more (closing would write into it again), and its handles are left
// to the operating system.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/sid/hdf5_io.h"
#include "runtime/output/disk_reservation.h"
#include "runtime/output/writer_lock.h"

namespace ffriga {

constexpr const char* kResultFormat = "ffriga-result";
constexpr int kResultFormatVersion = 6;

class ResultFile {
 public:
  // A series: one dataset [rows] (cols = 0) or [rows, cols] of doubles or integers.
  class Series {
   public:
    // Appends one row (max(cols, 1) values; integer series store them rounded towards 0).
    void append(const double* row) { pending_.insert(pending_.end(), row, row + width()); }
    int width() const { return cols_ > 0 ? cols_ : 1; }

   private:
    friend class ResultFile;
    h5::Handle dataset_;
    int cols_ = 0;
    bool integer_ = false;
    std::vector<double> pending_;  // rows appended since the last flush, row-major
  };

  // Creates (truncates) `path`, or with `appending` opens it for a restart (clearing the
  // "open for writing" mark of a killed run). InputError if it cannot be created or opened,
  // or if another ffrsim writes it.
  ResultFile(const std::string& path, bool appending);
  ~ResultFile();
  ResultFile(const ResultFile&) = delete;
  ResultFile& operator=(const ResultFile&) = delete;

  const std::string& path() const { return path_; }
  hid_t id() const { return file_.id(); }
  bool appending() const { return appending_; }
  bool open() const { return file_.id() >= 0; }
  // Whether rows can still be written: open and not broken.
  bool writable() const { return open() && !broken_; }
  bool swmr() const { return swmr_; }
  h5::Context context() const { return h5::Context{path_}; }

  // The group `name` below `parent` (created, or opened when appending).
  h5::Handle group(hid_t parent, const std::string& name);
  // A series below `parent` with its unit and description (when appending: the existing
  // dataset, which must have this shape).
  Series& series(hid_t parent, const std::string& name, int cols, const std::string& unit,
                 const std::string& description, bool integer = false);
  // Rows on disk and rows appended (all series grow together).
  long rowsWritten() const { return written_; }
  // Cuts every series back to `rows` rows (a restart).
  void truncate(long rows);
  // Writes every series' pending rows (`rows`: the row count afterwards).
  void writeRows(long rows);
  // H5Fflush of the whole file.
  void flushFile();
  // Reserves room on disk for the next writeRows() and `more` bytes besides (frames):
  // ComputeError, with nothing written, if the disk or the file size limit has no room.
  void reserve(std::uint64_t more);
  // The bytes written since the last reserve() exceeded its estimate by this much at most
  // (the next reservations add it); measured at every flush.
  void measureGrowth();
  // Switches to SWMR mode (after every object of the run is created).
  void startSwmr();
  // A write failed half-way: nothing more is written or closed.
  void markBroken() { broken_ = true; }

  // Root attributes (replaced if present).
  void setAttribute(const std::string& name, const std::string& value);
  void setAttribute(const std::string& name, double value);
  void setAttribute(const std::string& name, long value);
  // Attributes of an object of the file (a group or dataset, by its path, e.g.
  // "/contacts/impact"), replaced if present. In SWMR mode these and the root attributes
  // are kept and written at close.
  void setObjectAttribute(const std::string& object, const std::string& name, double value);
  void setObjectAttribute(const std::string& object, const std::string& name,
                          const std::string& value);

  // Writes a whole fixed-size dataset below `group` in place (row-major, as h5::writeMatrix
  // stores it; the same shape): what sinks rewrite at a flush, also in SWMR mode.
  void rewrite(hid_t group, const std::string& name, const Eigen::MatrixXd& m);

  // Removes an object (by its path) at close, or now outside SWMR mode.
  void removeObject(const std::string& object);

  // Closes the datasets and the file (other handles of the file must be closed before),
  // then writes the attributes kept in SWMR mode; later calls do nothing. A broken file is
  // not closed.
  void close();

 private:
  // An attribute or removal kept for the closing phase.
  struct Deferred {
    std::string object;  // "/" for the root
    std::string name;    // empty: remove `object`
    enum class Kind { kString, kDouble, kLong } kind = Kind::kString;
    std::string text;
    double number = 0.0;
    long integer = 0;
  };
  void writePending(Series& s);
  void apply(const Deferred& d);
  void reopenForClosing();
  std::uint64_t pendingBytes() const;
  std::uint64_t endOfFile() const;
  std::string path_;
  bool appending_ = false;
  bool swmr_ = false;
  bool broken_ = false;
  std::unique_ptr<WriterLock> lock_;
  std::unique_ptr<DiskReservation> space_;
  h5::Handle file_;
  std::vector<std::unique_ptr<Series>> series_;
  std::vector<Deferred> deferred_;
  long written_ = 0;  // rows on disk
  std::uint64_t estimate_end_ = 0;  // the end the last reservation expected after the flush
  std::uint64_t overshoot_ = 0;     // largest growth beyond an estimate so far
};

}  // namespace ffriga
