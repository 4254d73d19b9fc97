// One invocation of ffrsim in its phases (deal.II style; ffrsim_main.cc parses the command
// line and calls run()):
//
//   load       the scene and its SIDs, or for --restart the record, the scene text and the
//              SIDs the run used (the output path checked before any work)
//   open       the result file: its attributes (origin, warnings, preload, provenance)
//   attach     Hertz's references and the outputs that use them (stresses along lines at the
//              force peak), the visualisation frames
//   integrate  the time loop (runtime/simulation/simulation.h)
//   report     the comparison with Hertz into the file, the file closed, the summary printed
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "runtime/output/restart_record.h"
#include "runtime/output/result_writer.h"
#include "runtime/report/hertz_reference.h"
#include "runtime/scene/scene.h"
#include "runtime/simulation/simulation.h"

namespace ffriga {

// What the command line asks for (ffrsim --help).
struct FfrsimConfig {
  std::string scene_file;               // SCENE.yaml (empty with --restart)
  std::string output;                   // -o RESULT.h5, or the --restart file
  bool restart = false;                 // --restart: continue `output`
  double end_time = -1.0;               // --end-time T (s), with --restart; < 0: the run's
  std::vector<std::string> sid_paths;   // --sid-path DIR...
  std::vector<std::string> sets;        // --set KEY=VALUE...
  int verbosity = 1;                    // -q 0, -v 2
};

class FfrsimRun {
 public:
  explicit FfrsimRun(FfrsimConfig config);
  ~FfrsimRun();
  // The phases in order; returns the exit code (0 completed, 1 interrupted). Throws
  // InputError (bad input) and ComputeError (a failure while computing).
  int run();

 private:
  bool load();
  void open();
  void attach();
  SimulationReport integrate();
  int report(const SimulationReport& simulation);

  FfrsimConfig config_;
  RestartRecord record_;
  Scene scene_;
  std::unique_ptr<ResultWriter> writer_;
  HertzReferences hertz_;
};

}  // namespace ffriga
