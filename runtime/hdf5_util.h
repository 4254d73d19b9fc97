// Checked HDF5 helpers of the result file (on top of common/hdf5_io.h): every call's return
// code is checked and a failure becomes ComputeError naming the call, the object and the
// file. HDF5's own error printing is switched off (the message carries what matters).
#pragma once

#include <string>
#include <vector>

#include <hdf5.h>

#include "common/hdf5_io.h"  // Handle, silenceErrors

namespace ffriga::h5 {

// Throws ComputeError("HDF5: WHAT failed (FILE)") if status < 0; returns status.
hid_t check(hid_t status, const std::string& what, const std::string& file);

// Attributes on any object, replaced if present (the result file rewrites its status).
void writeAttribute(hid_t obj, const std::string& name, const std::string& value,
                    const std::string& file);
void writeAttribute(hid_t obj, const std::string& name, double value, const std::string& file);
void writeAttribute(hid_t obj, const std::string& name, long value, const std::string& file);
std::string readStringAttribute(hid_t obj, const std::string& name, const std::string& file);
double readDoubleAttribute(hid_t obj, const std::string& name, const std::string& file);

}  // namespace ffriga::h5
