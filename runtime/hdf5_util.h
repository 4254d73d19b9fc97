// Thin checked wrappers around the HDF5 C API used by the result file: every call's return
// code is checked and a failure becomes ComputeError naming the call, the object and the
// file. HDF5's own error printing is switched off (the message carries what matters).
#pragma once

#include <string>
#include <vector>

#include <hdf5.h>

namespace ffriga::h5 {

// Throws ComputeError("HDF5: WHAT failed (FILE)") if status < 0; returns status.
hid_t check(hid_t status, const std::string& what, const std::string& file);

// RAII handle: closes with the right H5?close on destruction.
class Handle {
 public:
  Handle() = default;
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() { reset(); }
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  Handle& operator=(Handle&& o) noexcept {
    reset();
    id_ = o.id_;
    close_ = o.close_;
    o.id_ = -1;
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t id() const { return id_; }
  void reset() {
    if (id_ >= 0 && close_) close_(id_);
    id_ = -1;
  }

 private:
  hid_t id_ = -1;
  herr_t (*close_)(hid_t) = nullptr;
};

void silenceErrors();
// Attributes on any object (replaced if present).
void writeAttribute(hid_t obj, const std::string& name, const std::string& value,
                    const std::string& file);
void writeAttribute(hid_t obj, const std::string& name, double value, const std::string& file);
void writeAttribute(hid_t obj, const std::string& name, long value, const std::string& file);
std::string readStringAttribute(hid_t obj, const std::string& name, const std::string& file);
double readDoubleAttribute(hid_t obj, const std::string& name, const std::string& file);

}  // namespace ffriga::h5
