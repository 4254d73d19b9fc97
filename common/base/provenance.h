// What a result or SID file was made by: the program's version and the git revision of
// its source tree (common/cmake/GitRevision.cmake), the versions of the libraries it was
// compiled against, and the number of OpenMP threads. Written as attributes of the output
// files' /provenance groups (schemas/sid_format.md, schemas/result_format.md).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace ffriga {

std::string gitRevision();
// The line --version prints: "PROGRAM VERSION (git REVISION)". The workflow of studies
// hashes it into the names of cached SIDs and runs (benchmarks/studies/study_file.py), so
// that another build of another source tree never reuses what this one made.
std::string versionLine(const std::string& program);
// (library, version) in a fixed order: Eigen, HDF5, SUNDIALS, SuiteSparse, yaml-cpp.
std::vector<std::pair<std::string, std::string>> dependencyVersions();
// "Eigen 3.4.0, HDF5 1.10.8, ..." (one line).
std::string dependencyVersionsText();
int ompThreads();

}  // namespace ffriga
