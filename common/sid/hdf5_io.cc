#include "common/sid/hdf5_io.h"

#include "common/base/error.h"

namespace ffriga::h5 {

namespace {
// HDF5's exit handler closes every file still open at exit. A file whose write or close
// failed (a full disk) is still registered, and closing it a second time there crashes
// (seen: SIGSEGV in H5F__close_cb after a failed H5Fflush). The programs close their files
// themselves, so the handler is switched off before the library starts: a file that could
// not be closed is left to the operating system, and nothing more is written into it.
const bool kNoExitHandler = H5dont_atexit() >= 0;
}  // namespace

bool exitHandlerDisabled() { return kNoExitHandler; }

Handle& Handle::operator=(Handle&& o) noexcept {
  if (this != &o) {
    if (id_ >= 0 && close_) close_(id_);
    id_ = o.id_;
    close_ = o.close_;
    o.id_ = -1;
  }
  return *this;
}

Handle::~Handle() {
  if (id_ >= 0 && close_) close_(id_);
}

namespace {
// The operating system's reason for the failure on top of HDF5's error stack, if one is
// there (the file drivers record it as "error message = '...'", e.g. "No space left on
// device" or "File too large"), else "".
herr_t findSystemError(unsigned, const H5E_error2_t* e, void* data) {
  auto* reason = static_cast<std::string*>(data);
  if (!reason->empty() || !e || !e->desc) return 0;
  const std::string desc = e->desc;
  const std::string key = "error message = '";
  const auto at = desc.find(key);
  if (at == std::string::npos) return 0;
  const auto end = desc.find('\'', at + key.size());
  *reason = desc.substr(at + key.size(), end == std::string::npos ? end : end - at - key.size());
  return 0;
}

}  // namespace

std::string systemErrorOnStack() {
  std::string reason;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, findSystemError, &reason);
  return reason;
}

void Context::fail(const std::string& what) const {
  const std::string msg = Str() << file << ": " << what;
  if (reading) throw InputError(msg);
  throw ComputeError(msg);
}

void Context::failCall(const std::string& what) const {
  const std::string reason = systemErrorOnStack();
  fail("HDF5 call failed: " + what + (reason.empty() ? "" : " (" + reason + ")"));
}

hid_t Context::check(hid_t id, const std::string& what) const {
  if (id < 0) failCall(what);
  return id;
}

void Context::check(herr_t status, const std::string& what, int) const {
  if (status < 0) failCall(what);
}

void silenceErrors() {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

Handle createGroup(const Context& c, hid_t parent, const std::string& name) {
  return Handle(c.check(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                        "create group " + name),
                H5Gclose);
}

Handle openGroup(const Context& c, hid_t parent, const std::string& name) {
  if (!exists(parent, name)) c.fail("missing group '" + name + "' (not a complete SID file?)");
  return Handle(c.check(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), "open group " + name),
                H5Gclose);
}

bool exists(hid_t parent, const std::string& name) {
  return H5Lexists(parent, name.c_str(), H5P_DEFAULT) > 0;
}

namespace {

void writeRaw(const Context& c, hid_t parent, const std::string& name,
              const std::vector<hsize_t>& dims, hid_t memType, hid_t fileType, const void* data,
              const std::string& units) {
  Handle space(c.check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                       "dataspace of " + name),
               H5Sclose);
  Handle set(c.check(H5Dcreate2(parent, name.c_str(), fileType, space, H5P_DEFAULT, H5P_DEFAULT,
                                H5P_DEFAULT),
                     "create dataset " + name),
             H5Dclose);
  static const double dummy = 0.0;
  c.check(H5Dwrite(set, memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, data ? data : &dummy),
          "write dataset " + name, 0);
  if (!units.empty()) writeAttribute(c, set, "units", units);
}

Handle openDataset(const Context& c, hid_t parent, const std::string& name,
                   std::vector<hsize_t>* dims) {
  if (!exists(parent, name)) c.fail("missing dataset '" + name + "'");
  Handle set(c.check(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), "open dataset " + name),
             H5Dclose);
  Handle space(c.check(H5Dget_space(set), "dataspace of " + name), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 0) c.fail("rank of dataset " + name);
  dims->assign(rank, 0);
  c.check(H5Sget_simple_extent_dims(space, dims->data(), nullptr), "dims of " + name, 0);
  return set;
}

std::size_t product(const std::vector<hsize_t>& dims) {
  std::size_t n = 1;
  for (hsize_t d : dims) n *= static_cast<std::size_t>(d);
  return n;
}

}  // namespace

void writeArray(const Context& c, hid_t parent, const std::string& name,
                const std::vector<hsize_t>& dims, const std::vector<double>& data,
                const std::string& units) {
  writeRaw(c, parent, name, dims, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE,
           data.empty() ? nullptr : data.data(), units);
}

void writeMatrix(const Context& c, hid_t parent, const std::string& name, const Eigen::MatrixXd& m,
                 const std::string& units, bool single) {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const RowMajor r = m;
  writeRaw(c, parent, name, {static_cast<hsize_t>(m.rows()), static_cast<hsize_t>(m.cols())},
           H5T_NATIVE_DOUBLE, single ? H5T_IEEE_F32LE : H5T_IEEE_F64LE,
           r.size() ? r.data() : nullptr, units);
}

void writeVector(const Context& c, hid_t parent, const std::string& name, const Eigen::VectorXd& v,
                 const std::string& units) {
  writeRaw(c, parent, name, {static_cast<hsize_t>(v.size())}, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE,
           v.size() ? v.data() : nullptr, units);
}

void writeInts(const Context& c, hid_t parent, const std::string& name, const std::vector<int>& v) {
  writeRaw(c, parent, name, {static_cast<hsize_t>(v.size())}, H5T_NATIVE_INT, H5T_STD_I32LE,
           v.empty() ? nullptr : v.data(), "");
}

void writeIntMatrix(const Context& c, hid_t parent, const std::string& name,
                    const Eigen::MatrixXi& m) {
  using RowMajor = Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const RowMajor r = m;
  writeRaw(c, parent, name, {static_cast<hsize_t>(m.rows()), static_cast<hsize_t>(m.cols())},
           H5T_NATIVE_INT, H5T_STD_I32LE, r.size() ? r.data() : nullptr, "");
}

void writeScalar(const Context& c, hid_t parent, const std::string& name, double v,
                 const std::string& units) {
  Handle space(c.check(H5Screate(H5S_SCALAR), "scalar dataspace"), H5Sclose);
  Handle set(c.check(H5Dcreate2(parent, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT,
                                H5P_DEFAULT, H5P_DEFAULT),
                     "create dataset " + name),
             H5Dclose);
  c.check(H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v),
          "write dataset " + name, 0);
  if (!units.empty()) writeAttribute(c, set, "units", units);
}

std::vector<double> readArray(const Context& c, hid_t parent, const std::string& name,
                              std::vector<hsize_t>* dims) {
  Handle set = openDataset(c, parent, name, dims);
  std::vector<double> data(product(*dims));
  if (!data.empty()) {
    c.check(H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
            "read dataset " + name, 0);
  }
  return data;
}

Eigen::MatrixXd readMatrix(const Context& c, hid_t parent, const std::string& name) {
  std::vector<hsize_t> dims;
  Handle set = openDataset(c, parent, name, &dims);
  if (dims.size() != 2)
    c.fail(Str() << "dataset " << name << " has rank " << dims.size() << ", expected 2");
  // Straight into a row-major matrix (the file's order), then one transposing copy: large
  // mode matrices are read without a third copy in between.
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  RowMajor r(static_cast<Eigen::Index>(dims[0]), static_cast<Eigen::Index>(dims[1]));
  if (r.size() > 0) {
    c.check(H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, r.data()),
            "read dataset " + name, 0);
  }
  return r;
}

Eigen::VectorXd readVector(const Context& c, hid_t parent, const std::string& name) {
  std::vector<hsize_t> dims;
  const std::vector<double> data = readArray(c, parent, name, &dims);
  if (dims.size() != 1)
    c.fail(Str() << "dataset " << name << " has rank " << dims.size() << ", expected 1");
  return Eigen::Map<const Eigen::VectorXd>(data.data(), static_cast<Eigen::Index>(data.size()));
}

std::vector<int> readInts(const Context& c, hid_t parent, const std::string& name) {
  std::vector<hsize_t> dims;
  Handle set = openDataset(c, parent, name, &dims);
  std::vector<int> v(product(dims));
  if (!v.empty()) {
    c.check(H5Dread(set, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()),
            "read dataset " + name, 0);
  }
  return v;
}

Eigen::MatrixXi readIntMatrix(const Context& c, hid_t parent, const std::string& name) {
  std::vector<hsize_t> dims;
  Handle set = openDataset(c, parent, name, &dims);
  if (dims.size() != 2)
    c.fail(Str() << "dataset " << name << " has rank " << dims.size() << ", expected 2");
  using RowMajor = Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  RowMajor m(static_cast<Eigen::Index>(dims[0]), static_cast<Eigen::Index>(dims[1]));
  if (m.size() > 0) {
    c.check(H5Dread(set, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, m.data()),
            "read dataset " + name, 0);
  }
  return m;
}

double readScalar(const Context& c, hid_t parent, const std::string& name) {
  std::vector<hsize_t> dims;
  Handle set = openDataset(c, parent, name, &dims);
  if (product(dims) != 1) c.fail("dataset " + name + " is not a scalar");
  double v = 0.0;
  c.check(H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v),
          "read dataset " + name, 0);
  return v;
}

namespace {
// Attributes are replaced if present (the result file rewrites its status as it runs).
void removeAttribute(const Context& c, hid_t obj, const std::string& name) {
  const htri_t exists = H5Aexists(obj, name.c_str());
  c.check(static_cast<herr_t>(exists), "look up attribute " + name, 0);
  if (exists > 0) c.check(H5Adelete(obj, name.c_str()), "replace attribute " + name, 0);
}
}  // namespace

void writeAttribute(const Context& c, hid_t obj, const std::string& name, const std::string& v) {
  removeAttribute(c, obj, name);
  // Variable-length UTF-8 (h5py reads it as str, not bytes).
  Handle type(c.check(H5Tcopy(H5T_C_S1), "string type"), H5Tclose);
  c.check(H5Tset_size(type, H5T_VARIABLE), "string size", 0);
  c.check(H5Tset_cset(type, H5T_CSET_UTF8), "string charset", 0);
  Handle space(c.check(H5Screate(H5S_SCALAR), "scalar dataspace"), H5Sclose);
  Handle attr(c.check(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT),
                      "create attribute " + name),
              H5Aclose);
  const char* data = v.c_str();
  c.check(H5Awrite(attr, type, &data), "write attribute " + name, 0);
}

namespace {
// Writes `v` into an existing scalar attribute `name` of the same class and size as
// `fileType`, in place; false if there is none (then it is replaced). In place, the object
// header keeps its size: what a file in SWMR mode allows (runtime/output/result_file.h).
bool overwriteAttribute(const Context& c, hid_t obj, const std::string& name, hid_t fileType,
                        hid_t memType, const void* v) {
  const htri_t exists = H5Aexists(obj, name.c_str());
  c.check(static_cast<herr_t>(exists), "look up attribute " + name, 0);
  if (exists <= 0) return false;
  Handle attr(c.check(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "open attribute " + name),
              H5Aclose);
  Handle type(c.check(H5Aget_type(attr), "type of attribute " + name), H5Tclose);
  Handle space(c.check(H5Aget_space(attr), "space of attribute " + name), H5Sclose);
  if (H5Tget_class(type) != H5Tget_class(fileType) || H5Tget_size(type) != H5Tget_size(fileType) ||
      H5Sget_simple_extent_type(space) != H5S_SCALAR) {
    return false;
  }
  c.check(H5Awrite(attr, memType, v), "write attribute " + name, 0);
  return true;
}
}  // namespace

void writeAttribute(const Context& c, hid_t obj, const std::string& name, double v) {
  if (overwriteAttribute(c, obj, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &v)) return;
  removeAttribute(c, obj, name);
  Handle space(c.check(H5Screate(H5S_SCALAR), "scalar dataspace"), H5Sclose);
  Handle attr(
      c.check(H5Acreate2(obj, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT),
              "create attribute " + name),
      H5Aclose);
  c.check(H5Awrite(attr, H5T_NATIVE_DOUBLE, &v), "write attribute " + name, 0);
}

void writeAttribute(const Context& c, hid_t obj, const std::string& name, long v) {
  if (overwriteAttribute(c, obj, name, H5T_STD_I64LE, H5T_NATIVE_LONG, &v)) return;
  removeAttribute(c, obj, name);
  Handle space(c.check(H5Screate(H5S_SCALAR), "scalar dataspace"), H5Sclose);
  Handle attr(c.check(H5Acreate2(obj, name.c_str(), H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT),
                      "create attribute " + name),
              H5Aclose);
  c.check(H5Awrite(attr, H5T_NATIVE_LONG, &v), "write attribute " + name, 0);
}

void writeAttribute(const Context& c, hid_t obj, const std::string& name, int v) {
  if (overwriteAttribute(c, obj, name, H5T_STD_I32LE, H5T_NATIVE_INT, &v)) return;
  removeAttribute(c, obj, name);
  Handle space(c.check(H5Screate(H5S_SCALAR), "scalar dataspace"), H5Sclose);
  Handle attr(c.check(H5Acreate2(obj, name.c_str(), H5T_STD_I32LE, space, H5P_DEFAULT, H5P_DEFAULT),
                      "create attribute " + name),
              H5Aclose);
  c.check(H5Awrite(attr, H5T_NATIVE_INT, &v), "write attribute " + name, 0);
}

bool hasAttribute(hid_t obj, const std::string& name) {
  return H5Aexists(obj, name.c_str()) > 0;
}

namespace {
Handle openAttribute(const Context& c, hid_t obj, const std::string& name) {
  if (!hasAttribute(obj, name)) c.fail("missing attribute '" + name + "'");
  return Handle(c.check(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "open attribute " + name),
                H5Aclose);
}
}  // namespace

std::string readStringAttribute(const Context& c, hid_t obj, const std::string& name) {
  Handle attr = openAttribute(c, obj, name);
  Handle type(c.check(H5Aget_type(attr), "type of attribute " + name), H5Tclose);
  if (H5Tget_class(type) != H5T_STRING) c.fail("attribute '" + name + "' is not a string");
  if (H5Tis_variable_str(type) > 0) {
    Handle memType(c.check(H5Tcopy(H5T_C_S1), "string type"), H5Tclose);
    c.check(H5Tset_size(memType, H5T_VARIABLE), "string size", 0);
    c.check(H5Tset_cset(memType, H5Tget_cset(type)), "string charset", 0);
    char* data = nullptr;
    c.check(H5Aread(attr, memType, &data), "read attribute " + name, 0);
    std::string out = data ? data : "";
    Handle space(c.check(H5Aget_space(attr), "space of attribute " + name), H5Sclose);
    H5Dvlen_reclaim(memType, space, H5P_DEFAULT, &data);
    return out;
  }
  // Fixed-length (files written before SID format 3 and result format 4).
  const std::size_t size = H5Tget_size(type);
  if (size == 0) c.fail("size of attribute " + name);
  std::string buf(size, '\0');
  c.check(H5Aread(attr, type, buf.data()), "read attribute " + name, 0);
  const auto end = buf.find('\0');
  if (end != std::string::npos) buf.resize(end);
  return buf;
}

double readDoubleAttribute(const Context& c, hid_t obj, const std::string& name) {
  Handle attr = openAttribute(c, obj, name);
  double v = 0.0;
  c.check(H5Aread(attr, H5T_NATIVE_DOUBLE, &v), "read attribute " + name, 0);
  return v;
}

int readIntAttribute(const Context& c, hid_t obj, const std::string& name) {
  Handle attr = openAttribute(c, obj, name);
  int v = 0;
  c.check(H5Aread(attr, H5T_NATIVE_INT, &v), "read attribute " + name, 0);
  return v;
}

namespace {
herr_t collectName(hid_t, const char* name, const H5L_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->push_back(name);
  return 0;
}
}  // namespace

std::vector<std::string> listGroup(const Context& c, hid_t group) {
  std::vector<std::string> names;
  hsize_t idx = 0;
  c.check(H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, &idx, collectName, &names), "list group",
          0);
  return names;
}

}  // namespace ffriga::h5
