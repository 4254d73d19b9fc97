// Checked helpers around the HDF5 C API (1.10): RAII handles, datasets of doubles and ints
// (matrices stored row-major as [rows, cols]), variable-length UTF-8 string attributes
// (reading also the fixed-length ones of older files) and scalar attributes.
// Every call's return code is checked; failures throw the error type chosen by the caller
// (ComputeError when writing, InputError when reading a user's file) naming the object.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <hdf5.h>
#include <Eigen/Dense>

namespace ffriga::h5 {

// Owns an hid_t and closes it with the matching H5*close.
class Handle {
 public:
  Handle() = default;
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  Handle& operator=(Handle&& o) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle();
  hid_t get() const { return id_; }
  hid_t id() const { return id_; }
  void reset() {
    if (id_ >= 0 && close_) close_(id_);
    id_ = -1;
  }
  // Forgets the id without closing it (an object of a file whose writes failed: closing it
  // would write into the file again).
  void release() { id_ = -1; }
  operator hid_t() const { return id_; }

 private:
  hid_t id_ = -1;
  herr_t (*close_)(hid_t) = nullptr;
};

// Context for messages and the exception to throw.
struct Context {
  std::string file;
  bool reading = false;
  [[noreturn]] void fail(const std::string& what) const;
  // fail("HDF5 call failed: <what>"), with the operating system's reason when HDF5 recorded
  // one (e.g. "(No space left on device)").
  [[noreturn]] void failCall(const std::string& what) const;
  hid_t check(hid_t id, const std::string& what) const;
  void check(herr_t status, const std::string& what, int) const;
};

void silenceErrors();
// The operating system's reason for the last failed HDF5 call, if HDF5 recorded one (e.g.
// "No space left on device", "Resource temporarily unavailable" for a locked file), else "".
std::string systemErrorOnStack();
// Whether HDF5's exit handler was switched off before the library started (hdf5_io.cc: a
// file whose close failed must not be closed again at exit).
bool exitHandlerDisabled();

Handle createGroup(const Context& c, hid_t parent, const std::string& name);
Handle openGroup(const Context& c, hid_t parent, const std::string& name);
bool exists(hid_t parent, const std::string& name);

// single: stored as 4-byte floats (pictures, not records); read back as doubles.
void writeMatrix(const Context& c, hid_t parent, const std::string& name, const Eigen::MatrixXd& m,
                 const std::string& units, bool single = false);
void writeVector(const Context& c, hid_t parent, const std::string& name, const Eigen::VectorXd& v,
                 const std::string& units);
void writeInts(const Context& c, hid_t parent, const std::string& name, const std::vector<int>& v);
void writeIntMatrix(const Context& c, hid_t parent, const std::string& name,
                    const Eigen::MatrixXi& m);
void writeScalar(const Context& c, hid_t parent, const std::string& name, double v,
                 const std::string& units);
// Any dimensions (row-major), e.g. [nq, 3, nq].
void writeArray(const Context& c, hid_t parent, const std::string& name,
                const std::vector<hsize_t>& dims, const std::vector<double>& data,
                const std::string& units);

Eigen::MatrixXd readMatrix(const Context& c, hid_t parent, const std::string& name);
Eigen::VectorXd readVector(const Context& c, hid_t parent, const std::string& name);
std::vector<int> readInts(const Context& c, hid_t parent, const std::string& name);
Eigen::MatrixXi readIntMatrix(const Context& c, hid_t parent, const std::string& name);
double readScalar(const Context& c, hid_t parent, const std::string& name);
std::vector<double> readArray(const Context& c, hid_t parent, const std::string& name,
                              std::vector<hsize_t>* dims);

// Attributes are written as scalars, replacing an attribute of the same name (numbers into
// an attribute of the same type in place, which a file in SWMR mode allows).
void writeAttribute(const Context& c, hid_t obj, const std::string& name, const std::string& v);
void writeAttribute(const Context& c, hid_t obj, const std::string& name, double v);
void writeAttribute(const Context& c, hid_t obj, const std::string& name, int v);
void writeAttribute(const Context& c, hid_t obj, const std::string& name, long v);
std::string readStringAttribute(const Context& c, hid_t obj, const std::string& name);
double readDoubleAttribute(const Context& c, hid_t obj, const std::string& name);
int readIntAttribute(const Context& c, hid_t obj, const std::string& name);
bool hasAttribute(hid_t obj, const std::string& name);
// Names of the links in a group, in creation order... (name order).
std::vector<std::string> listGroup(const Context& c, hid_t group);

}  // namespace ffriga::h5
