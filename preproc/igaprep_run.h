// One invocation of igaprep in its phases (igaprep_main.cc parses the command line and
// calls run()):
//
//   info        --info FILE: the summary of a SID file, nothing else
//   load        the output path checked (before any work), the body file read and checked
//               (preproc/input/body_config.h), the size estimate against --max-memory
//   describe    without -o: the refined geometry and the hierarchy, nothing written
//   preprocess  the pipeline (preproc/body_preprocessor.h)
//   write       the SID file, atomically (common/sid/sid_file.h), and the summary
#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace ffriga {

// What the command line asks for (igaprep --help).
struct IgaprepConfig {
  std::string body_file;            // BODY.yaml
  std::string output;               // -o BODY.sid.h5 (empty: geometry summary only)
  std::string info;                 // --info FILE.sid.h5
  double max_memory_gib = 0.0;      // --max-memory GIB; 0: this machine's physical memory
  std::vector<std::string> sets;    // --set KEY=VALUE...
  int verbosity = 1;                // -q 0, -v 2
};

class IgaprepRun {
 public:
  explicit IgaprepRun(IgaprepConfig config);
  // The phases in order; returns the exit code 0. Throws InputError (bad input) and
  // ComputeError (a failure while computing).
  int run();

 private:
  IgaprepConfig config_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace ffriga
