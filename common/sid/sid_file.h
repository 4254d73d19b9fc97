// SID files: one HDF5 file per reduced flexible body (layout and units in
// schemas/sid_format.md, format "ffriga-sid", version kSidFormatVersion).
//
// writeSid is atomic: the file is written as "PATH.tmp-PID" and renamed to PATH; on any
// failure the temporary file is removed and nothing is left behind (ComputeError).
// readSid throws InputError naming the file for a missing or unreadable file, a wrong
// `format` or a `format_version` this program does not read, and for a value that is not
// finite (NaN, inf) in any real dataset it reads, naming the dataset and the entry:
// "FILE: dataset '/body/Phi': expected a finite number, found nan at [5, 1]" (0-based).
// Every HDF5 call's return code is checked; HDF5's own error printing is switched off and
// the failing call is named in the message instead.
#pragma once

#include <string>

#include "common/sid/sid.h"

namespace ffriga {

inline constexpr const char* kSidFormat = "ffriga-sid";
inline constexpr int kSidFormatVersion = 3;

// What readSid reads: everything, or everything but the visualisation mesh (then
// sid.mesh.empty()): its sampled displacement and stress modes are most of a large SID's
// bytes (sphere3d_h3: 594 of 1181 MB) and only visualisation frames use them.
enum class SidContent { kAll, kWithoutMesh };

void writeSid(const FlexibleBodySid& sid, const std::string& path);
FlexibleBodySid readSid(const std::string& path, SidContent content = SidContent::kAll);

}  // namespace ffriga
