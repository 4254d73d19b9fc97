#include "runtime/output/result_file.h"

#include <algorithm>

#include "common/base/error.h"

namespace ffriga {

using h5::Handle;

namespace {
// Checked HDF5 call of the result file (common/sid/hdf5_io.h: ComputeError naming the file).
hid_t check(hid_t status, const std::string& what, const std::string& file) {
  return h5::Context{file}.check(status, what);
}
}  // namespace

ResultFile::ResultFile(const std::string& path, bool appending)
    : path_(path), appending_(appending) {
  h5::silenceErrors();
  const hid_t f = appending_ ? H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT)
                             : H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (f < 0) {
    throw InputError(Str() << path << ": cannot " << (appending_ ? "open" : "create")
                           << " the result file");
  }
  file_ = Handle(f, H5Fclose);
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

void ResultFile::setAttribute(const std::string& name, const std::string& value) {
  h5::writeAttribute(context(), file_.id(), name, value);
}
void ResultFile::setAttribute(const std::string& name, double value) {
  h5::writeAttribute(context(), file_.id(), name, value);
}
void ResultFile::setAttribute(const std::string& name, long value) {
  h5::writeAttribute(context(), file_.id(), name, value);
}

void ResultFile::setObjectAttribute(const std::string& object, const std::string& name,
                                    double value) {
  const h5::Context c = context();
  Handle o(c.check(H5Oopen(file_.id(), object.c_str(), H5P_DEFAULT), "open " + object), H5Oclose);
  h5::writeAttribute(c, o.id(), name, value);
}
void ResultFile::setObjectAttribute(const std::string& object, const std::string& name,
                                    const std::string& value) {
  const h5::Context c = context();
  Handle o(c.check(H5Oopen(file_.id(), object.c_str(), H5P_DEFAULT), "open " + object), H5Oclose);
  h5::writeAttribute(c, o.id(), name, value);
}

void ResultFile::close() {
  if (file_.id() < 0) return;
  series_.clear();
  file_.reset();
}

}  // namespace ffriga
