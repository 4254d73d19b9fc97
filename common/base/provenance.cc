#include "common/base/provenance.h"

#include <hdf5.h>
#include <omp.h>
#include <openssl/crypto.h>
#include <suitesparse/SuiteSparse_config.h>
#include <sundials/sundials_config.h>

#include <Eigen/Core>

#include "common/base/error.h"
#include "common/base/git_revision.h"
#include "common/base/version.h"

namespace ffriga {

std::string versionLine(const std::string& program) {
  return program + " " + kVersion + " (git " + gitRevision() + ")";
}

std::string gitRevision() { return kGitRevision; }

std::vector<std::pair<std::string, std::string>> dependencyVersions() {
  unsigned major = 0, minor = 0, release = 0;
  H5get_libversion(&major, &minor, &release);  // the library linked, not the header's
  return {
      {"Eigen",
       Str() << EIGEN_WORLD_VERSION << "." << EIGEN_MAJOR_VERSION << "." << EIGEN_MINOR_VERSION},
      {"HDF5", Str() << major << "." << minor << "." << release},
      {"SUNDIALS", SUNDIALS_VERSION},
      {"SuiteSparse", Str() << SUITESPARSE_MAIN_VERSION << "." << SUITESPARSE_SUB_VERSION << "."
                            << SUITESPARSE_SUBSUB_VERSION},
      // yaml-cpp has no version macro: the one CMake found (common/CMakeLists.txt).
      {"yaml-cpp", FFRIGA_YAML_CPP_VERSION},
      {"OpenSSL", OpenSSL_version(OPENSSL_VERSION_STRING)},  // libcrypto: SHA-256
  };
}

std::string dependencyVersionsText() {
  std::string out;
  for (const auto& [name, version] : dependencyVersions())
    out += (out.empty() ? "" : ", ") + name + " " + version;
  return out;
}

int ompThreads() { return omp_get_max_threads(); }

}  // namespace ffriga
