#include "runtime/hdf5_util.h"

#include "common/error.h"

namespace ffriga::h5 {

hid_t check(hid_t status, const std::string& what, const std::string& file) {
  if (status < 0) throw ComputeError(Str() << "HDF5: " << what << " failed (" << file << ")");
  return status;
}

namespace {

void removeIfPresent(hid_t obj, const std::string& name, const std::string& file) {
  const htri_t exists = H5Aexists(obj, name.c_str());
  check(exists, "H5Aexists '" + name + "'", file);
  if (exists > 0) check(H5Adelete(obj, name.c_str()), "H5Adelete '" + name + "'", file);
}

void writeScalar(hid_t obj, const std::string& name, hid_t type, const void* value,
                 const std::string& file) {
  removeIfPresent(obj, name, file);
  Handle space(check(H5Screate(H5S_SCALAR), "H5Screate", file), H5Sclose);
  Handle attr(check(H5Acreate2(obj, name.c_str(), type, space.id(), H5P_DEFAULT, H5P_DEFAULT),
                    "H5Acreate2 '" + name + "'", file),
              H5Aclose);
  check(H5Awrite(attr.id(), type, value), "H5Awrite '" + name + "'", file);
}

}  // namespace

void writeAttribute(hid_t obj, const std::string& name, const std::string& value,
                    const std::string& file) {
  Handle type(check(H5Tcopy(H5T_C_S1), "H5Tcopy", file), H5Tclose);
  check(H5Tset_size(type.id(), value.empty() ? 1 : value.size()), "H5Tset_size", file);
  check(H5Tset_cset(type.id(), H5T_CSET_UTF8), "H5Tset_cset", file);
  const std::string padded = value.empty() ? std::string(1, '\0') : value;
  writeScalar(obj, name, type.id(), padded.data(), file);
}

void writeAttribute(hid_t obj, const std::string& name, double value, const std::string& file) {
  writeScalar(obj, name, H5T_NATIVE_DOUBLE, &value, file);
}

void writeAttribute(hid_t obj, const std::string& name, long value, const std::string& file) {
  writeScalar(obj, name, H5T_NATIVE_LONG, &value, file);
}

std::string readStringAttribute(hid_t obj, const std::string& name, const std::string& file) {
  Handle attr(check(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "H5Aopen '" + name + "'", file),
              H5Aclose);
  Handle type(check(H5Aget_type(attr.id()), "H5Aget_type", file), H5Tclose);
  const size_t n = H5Tget_size(type.id());
  if (n == 0) throw ComputeError(Str() << "HDF5: attribute '" << name << "' is not a string");
  std::string s(n, '\0');
  check(H5Aread(attr.id(), type.id(), &s[0]), "H5Aread '" + name + "'", file);
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

double readDoubleAttribute(hid_t obj, const std::string& name, const std::string& file) {
  Handle attr(check(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "H5Aopen '" + name + "'", file),
              H5Aclose);
  double v = 0.0;
  check(H5Aread(attr.id(), H5T_NATIVE_DOUBLE, &v), "H5Aread '" + name + "'", file);
  return v;
}

}  // namespace ffriga::h5
