// ffrsim: flexible bodies in the floating frame of reference with NURBS penalty contact.
//
//   ffrsim SCENE.yaml -o RESULT.h5
//
// This version answers --help and --version; the simulation is being built (issue 5).
#include <iostream>

#include "common/cli.h"
#include "common/version.h"

namespace {

constexpr const char* kUsage = R"(usage: ffrsim SCENE.yaml -o RESULT.h5 [options]

Simulates impacts between reduced flexible bodies (SID files written by igaprep) in the
floating frame of reference with penalty contact between NURBS surfaces.

options:
  -o, --output FILE  result file (HDF5)
  -q, --quiet        print nothing but errors
  -v, --verbose      print more detail
  --threads N        number of OpenMP threads
  -h, --help         show this help and exit
  --version          show the version and exit

Exit codes: 0 success, 2 bad input or usage, 1 failure while computing.
)";

}  // namespace

int main(int argc, char** argv) {
  return ffriga::runProgram("ffrsim", [&]() {
    const ffriga::CommonOptions o = ffriga::parseCommonOptions(argc, argv);
    if (o.help) {
      std::cout << kUsage;
      return 0;
    }
    if (o.version) {
      std::cout << "ffrsim " << ffriga::kVersion << "\n";
      return 0;
    }
    throw ffriga::UsageError(
        "simulating scenes is not available in this version of ffrsim (see --help)");
  });
}
