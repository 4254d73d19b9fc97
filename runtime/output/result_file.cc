#include "runtime/output/result_file.h"

#include <algorithm>
#include <cstdint>

#include "common/base/error.h"

namespace ffriga {

using h5::Handle;

namespace {
// Checked HDF5 call of the result file (common/sid/hdf5_io.h: ComputeError naming the file).
hid_t check(hid_t status, const std::string& what, const std::string& file) {
  return h5::Context{file}.check(status, what);
}
}  // namespace

namespace {

// File access: the latest file format (SWMR needs it); for a restart also the clearing of
// the "open for writing" mark a killed run leaves (the property h5clear -s sets; safe here,
// under the writer lock: no other ffrsim writes the file). Without `locking`, HDF5 does not
// lock the file (its readers hold shared locks; the writer lock guards the writers).
Handle fileAccess(const std::string& path, bool clear_mark, bool locking = true) {
  Handle fapl(check(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate", path), H5Pclose);
  check(H5Pset_libver_bounds(fapl.id(), H5F_LIBVER_LATEST, H5F_LIBVER_LATEST),
        "H5Pset_libver_bounds", path);
  if (!locking) check(H5Pset_file_locking(fapl.id(), 0, 1), "H5Pset_file_locking", path);
  if (clear_mark && H5Pexist(fapl.id(), "clear_status_flags") > 0) {
    hbool_t clear = 1;
    check(H5Pset(fapl.id(), "clear_status_flags", &clear), "H5Pset clear_status_flags", path);
  }
  return fapl;
}

// Bytes a flush of the pending rows adds to a series of `written` rows: the chunks (256
// rows, allocated whole when first written) that it starts.
std::uint64_t chunkBytes(long written, std::size_t pending_values, int width) {
  if (pending_values == 0) return 0;
  const long rows = static_cast<long>(pending_values) / width;
  const long chunks = (written + rows + 255) / 256 - (written + 255) / 256;
  return static_cast<std::uint64_t>(chunks) * 256u * static_cast<std::uint64_t>(width) * 8u;
}

// Room for what is written besides the chunks: metadata of the grown datasets (chunk
// indexes, object headers), the final attributes and the close (a few kB; the growth
// beyond the estimates is measured and added, ResultFile::measureGrowth).
constexpr std::uint64_t kSlackBytes = std::uint64_t{256} << 10;

}  // namespace

ResultFile::ResultFile(const std::string& path, bool appending)
    : path_(path), appending_(appending) {
  h5::silenceErrors();
  lock_ = std::make_unique<WriterLock>(path);  // before HDF5 touches the file
  Handle fapl = fileAccess(path_, appending_);
  const hid_t f = appending_ ? H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl.id())
                             : H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.id());
  if (f < 0) {
    const std::string reason = h5::systemErrorOnStack();
    throw InputError(Str() << path << ": cannot " << (appending_ ? "open" : "create")
                           << " the result file"
                           << (reason.empty() ? "" : " (" + reason + "; is it open in another "
                                                         "program?)"));
  }
  file_ = Handle(f, H5Fclose);
  lock_->acquire();  // HDF5 may have opened and closed descriptors of the file
  space_ = std::make_unique<DiskReservation>(path_, lock_->descriptor());
}

ResultFile::~ResultFile() {
  try {
    close();
  } catch (...) {
    // Destructors must not throw; close() explicitly to see errors.
  }
}

Handle ResultFile::group(hid_t parent, const std::string& name) {
  if (appending_) return h5::openGroup(context(), parent, name);
  return Handle(check(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                      "H5Gcreate2 '" + name + "'", path_),
                H5Gclose);
}

ResultFile::Series& ResultFile::series(hid_t parent, const std::string& name, int cols,
                                       const std::string& unit, const std::string& description,
                                       bool integer) {
  auto s = std::make_unique<Series>();
  s->cols_ = cols;
  s->integer_ = integer;
  if (appending_) {  // a restart: the dataset exists and must have this shape
    s->dataset_ = Handle(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose);
    int found = -1;
    if (s->dataset_.id() >= 0) {
      Handle space(H5Dget_space(s->dataset_.id()), H5Sclose);
      hsize_t dims[2] = {0, 0};
      const int rank = H5Sget_simple_extent_dims(space.id(), dims, nullptr);
      found = rank == 1 ? 0 : rank == 2 ? static_cast<int>(dims[1]) : -2;
    }
    if (found != cols) {
      throw InputError(Str() << path_ << ": dataset '" << name << "' "
                             << (found == -1 ? "is missing" : "has another shape")
                             << ": the file was not written by this scene");
    }
    series_.push_back(std::move(s));
    return *series_.back();
  }
  const int rank = cols == 0 ? 1 : 2;
  const hsize_t dims[2] = {0, static_cast<hsize_t>(cols)};
  const hsize_t maxdims[2] = {H5S_UNLIMITED, static_cast<hsize_t>(cols)};
  const hsize_t chunk[2] = {256, static_cast<hsize_t>(std::max(cols, 1))};
  Handle space(check(H5Screate_simple(rank, dims, maxdims), "H5Screate_simple", path_), H5Sclose);
  Handle plist(check(H5Pcreate(H5P_DATASET_CREATE), "H5Pcreate", path_), H5Pclose);
  check(H5Pset_chunk(plist.id(), rank, chunk), "H5Pset_chunk", path_);
  const hid_t type = integer ? H5T_NATIVE_LONG : H5T_NATIVE_DOUBLE;
  s->dataset_ = Handle(check(H5Dcreate2(parent, name.c_str(), type, space.id(), H5P_DEFAULT,
                                        plist.id(), H5P_DEFAULT),
                             "H5Dcreate2 '" + name + "'", path_),
                       H5Dclose);
  h5::writeAttribute(context(), s->dataset_.id(), "unit", unit);
  h5::writeAttribute(context(), s->dataset_.id(), "description", description);
  series_.push_back(std::move(s));
  return *series_.back();
}

void ResultFile::truncate(long rows) {
  written_ = rows;
  for (auto& s : series_) {
    const hsize_t dims[2] = {static_cast<hsize_t>(rows), static_cast<hsize_t>(s->width())};
    check(H5Dset_extent(s->dataset_.id(), dims), "H5Dset_extent", path_);
  }
}

void ResultFile::writePending(Series& s) {
  const hsize_t n = static_cast<hsize_t>(s.width());
  const hsize_t count0 = s.pending_.size() / n;
  if (count0 == 0) return;
  const int rank = s.cols_ == 0 ? 1 : 2;
  const hsize_t newDims[2] = {static_cast<hsize_t>(written_) + count0, n};
  check(H5Dset_extent(s.dataset_.id(), newDims), "H5Dset_extent", path_);
  Handle fspace(check(H5Dget_space(s.dataset_.id()), "H5Dget_space", path_), H5Sclose);
  const hsize_t start[2] = {static_cast<hsize_t>(written_), 0};
  const hsize_t count[2] = {count0, n};
  check(H5Sselect_hyperslab(fspace.id(), H5S_SELECT_SET, start, nullptr, count, nullptr),
        "H5Sselect_hyperslab", path_);
  Handle mspace(check(H5Screate_simple(rank, count, nullptr), "H5Screate_simple", path_), H5Sclose);
  if (s.integer_) {
    std::vector<long> v(s.pending_.begin(), s.pending_.end());
    check(H5Dwrite(s.dataset_.id(), H5T_NATIVE_LONG, mspace.id(), fspace.id(), H5P_DEFAULT,
                   v.data()),
          "H5Dwrite", path_);
  } else {
    check(H5Dwrite(s.dataset_.id(), H5T_NATIVE_DOUBLE, mspace.id(), fspace.id(), H5P_DEFAULT,
                   s.pending_.data()),
          "H5Dwrite", path_);
  }
  s.pending_.clear();
}

void ResultFile::writeRows(long rows) {
  for (auto& s : series_) writePending(*s);
  written_ = rows;
}

void ResultFile::flushFile() { check(H5Fflush(file_.id(), H5F_SCOPE_GLOBAL), "H5Fflush", path_); }

void ResultFile::rewrite(hid_t group, const std::string& name, const Eigen::MatrixXd& m) {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const RowMajor r = m;
  const h5::Context c = context();
  h5::Handle set(c.check(H5Dopen2(group, name.c_str(), H5P_DEFAULT), "open " + name), H5Dclose);
  c.check(H5Dwrite(set.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, r.data()),
          "write " + name, 0);
}

std::uint64_t ResultFile::pendingBytes() const {
  std::uint64_t bytes = 0;
  for (const auto& s : series_) bytes += chunkBytes(written_, s->pending_.size(), s->width());
  return bytes;
}

std::uint64_t ResultFile::endOfFile() const {
  haddr_t eoa = 0;
  const std::uint64_t size = space_->fileSize();
  if (H5Fget_eoa(file_.id(), &eoa) < 0) return size;
  return std::max<std::uint64_t>(size, eoa);
}

void ResultFile::reserve(std::uint64_t more) {
  const std::uint64_t growth = pendingBytes() + more;
  const std::uint64_t end = endOfFile();
  estimate_end_ = end + growth;
  space_->ensure(end + growth + overshoot_ + kSlackBytes);
}

void ResultFile::measureGrowth() {
  const std::uint64_t end = endOfFile();
  if (estimate_end_ > 0 && end > estimate_end_) overshoot_ = std::max(overshoot_, end - estimate_end_);
}

void ResultFile::startSwmr() {
  if (swmr_) return;
  check(H5Fstart_swmr_write(file_.id()), "H5Fstart_swmr_write", path_);
  swmr_ = true;
}

void ResultFile::apply(const Deferred& d) {
  const h5::Context c = context();
  if (d.name.empty()) {
    if (h5::exists(file_.id(), d.object))
      c.check(H5Ldelete(file_.id(), d.object.c_str(), H5P_DEFAULT), "remove " + d.object, 0);
    return;
  }
  Handle o(c.check(H5Oopen(file_.id(), d.object.c_str(), H5P_DEFAULT), "open " + d.object),
           H5Oclose);
  switch (d.kind) {
    case Deferred::Kind::kString: h5::writeAttribute(c, o.id(), d.name, d.text); break;
    case Deferred::Kind::kDouble: h5::writeAttribute(c, o.id(), d.name, d.number); break;
    case Deferred::Kind::kLong: h5::writeAttribute(c, o.id(), d.name, d.integer); break;
  }
}

void ResultFile::setAttribute(const std::string& name, const std::string& value) {
  setObjectAttribute("/", name, value);
}
void ResultFile::setAttribute(const std::string& name, double value) {
  setObjectAttribute("/", name, value);
}
void ResultFile::setAttribute(const std::string& name, long value) {
  Deferred d{"/", name, Deferred::Kind::kLong, "", 0.0, value};
  if (swmr_)
    deferred_.push_back(d);
  else
    apply(d);
}

void ResultFile::setObjectAttribute(const std::string& object, const std::string& name,
                                    double value) {
  Deferred d{object, name, Deferred::Kind::kDouble, "", value, 0};
  if (swmr_)
    deferred_.push_back(d);
  else
    apply(d);
}
void ResultFile::setObjectAttribute(const std::string& object, const std::string& name,
                                    const std::string& value) {
  Deferred d{object, name, Deferred::Kind::kString, value, 0.0, 0};
  if (swmr_)
    deferred_.push_back(d);
  else
    apply(d);
}

void ResultFile::removeObject(const std::string& object) {
  Deferred d{object, "", Deferred::Kind::kString, "", 0.0, 0};
  if (swmr_)
    deferred_.push_back(d);
  else
    apply(d);
}

// The SWMR file closed, the file is opened again without SWMR for what SWMR mode does not
// allow (new attributes, strings, removals), for a few milliseconds. Readers may have it
// open (with shared HDF5 locks): it is opened without HDF5's lock; a reader that opens it
// in these milliseconds is refused ("already open for write") and tries again.
void ResultFile::reopenForClosing() {
  Handle fapl = fileAccess(path_, false, false);
  file_ = Handle(check(H5Fopen(path_.c_str(), H5F_ACC_RDWR, fapl.id()),
                       "H5Fopen (to write the run's final attributes)", path_),
                 H5Fclose);
  lock_->acquire();  // closing HDF5's descriptor dropped the record lock
  swmr_ = false;
}

void ResultFile::close() {
  if (file_.id() < 0) return;
  if (broken_) {  // closing would write into a file whose writes failed
    for (auto& s : series_) s->dataset_.release();
    series_.clear();
    file_.release();
    return;
  }
  series_.clear();
  const bool reopen = swmr_ && !deferred_.empty();
  const hid_t id = file_.id();
  file_.release();
  if (H5Fclose(id) < 0) {  // not closed again: HDF5 keeps what it could not write
    broken_ = true;
    h5::Context{path_}.failCall("H5Fclose");
  }
  if (reopen) {
    reopenForClosing();
    std::vector<Deferred> pending = std::move(deferred_);
    deferred_.clear();
    // The status last: once it leaves "running", the run's figures are there.
    std::stable_partition(pending.begin(), pending.end(), [](const Deferred& d) {
      return !(d.object == "/" && d.name == "status");
    });
    try {
      for (const Deferred& d : pending) apply(d);
    } catch (...) {
      broken_ = true;
      file_.release();
      throw;
    }
    const hid_t again = file_.id();
    file_.release();
    if (H5Fclose(again) < 0) {
      broken_ = true;
      h5::Context{path_}.failCall("H5Fclose");
    }
  }
  space_->release();
}

}  // namespace ffriga
