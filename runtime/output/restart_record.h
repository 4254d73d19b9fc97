// The restart record of a result file (group `restart`, schemas/result_format.md): at every
// flush the writer stores the full state vector y at the last row on disk, that row's time
// and the row count, and the run's figures so far (headline figures and solver statistics).
// `ffrsim --restart RESULT.h5` reads it back with the scene text and the SID files the run
// used, continues CVODE from there (a fresh start: order 1 at the restart time) and appends
// to the same file, after the record's row: no row is lost or repeated.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace ffriga {

struct RestartRecord {
  double time = 0.0;  // s, of the last row on disk
  long rows = 0;      // rows on disk consistent with `state`
  Eigen::VectorXd state;
  std::map<std::string, double> figures;  // by name: see simulation.cc (runFigures)
  // From the root attributes:
  std::string status;
  std::string scene_yaml;
  std::vector<std::string> overrides;  // the run's --set KEY=VALUE, applied to scene_yaml
  std::string scene_path;              // absolute, as at the first run
  std::vector<std::string> sid_files;  // absolute paths of the SIDs the run used
  double end_time = 0.0;               // s, the end time the run was going to
  long restarts = 0;                   // how often it was restarted already
};

// Reads the record of a result file; InputError (exit code 2) naming the file if it is not a
// result file of this format version or has no complete record yet.
RestartRecord readRestartRecord(const std::string& path);

}  // namespace ffriga
