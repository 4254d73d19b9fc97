// The HDF5 result file of ffrsim (layout, units and version: schemas/result_format.md) as
// the outputs write it: its root and group attributes, and series, chunked datasets with an
// unlimited first dimension that grow by one row per output time.
//
// Rows are kept in memory and written as one block per series at flush() (one HDF5 extent
// and write per series instead of one per row); flushFile() then flushes the HDF5 file.
// Opened for a restart (`appending`), the groups and series exist already: they are opened
// and checked for their shape instead of created, and every series is cut back to the rows
// of the restart record.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/sid/hdf5_io.h"

namespace ffriga {

constexpr const char* kResultFormat = "ffriga-result";
constexpr int kResultFormatVersion = 4;

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

  // Creates (truncates) `path`, or with `appending` opens it for a restart. InputError if it
  // cannot be created or opened.
  ResultFile(const std::string& path, bool appending);
  ~ResultFile();
  ResultFile(const ResultFile&) = delete;
  ResultFile& operator=(const ResultFile&) = delete;

  const std::string& path() const { return path_; }
  hid_t id() const { return file_.id(); }
  bool appending() const { return appending_; }
  bool open() const { return file_.id() >= 0; }
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

  // Root attributes (replaced if present).
  void setAttribute(const std::string& name, const std::string& value);
  void setAttribute(const std::string& name, double value);
  void setAttribute(const std::string& name, long value);
  // Attributes of an object of the file (a group or dataset, by its path, e.g.
  // "/contacts/impact"), replaced if present.
  void setObjectAttribute(const std::string& object, const std::string& name, double value);
  void setObjectAttribute(const std::string& object, const std::string& name,
                          const std::string& value);

  // Closes the datasets and the file; later calls do nothing.
  void close();

 private:
  void writePending(Series& s);
  std::string path_;
  bool appending_ = false;
  h5::Handle file_;
  std::vector<std::unique_ptr<Series>> series_;
  long written_ = 0;  // rows on disk
};

}  // namespace ffriga
