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

#include "runtime/output/output_sink.h"
#include "runtime/output/result_file.h"

namespace ffriga {

struct RestartRecord {
  double time = 0.0;  // s, of the last row on disk
  long rows = 0;      // rows on disk consistent with `state`
  Eigen::VectorXd state;
  double dissipated = 0.0;  // J, /energy/dissipated at that row (0 in records without it)
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

// Writes the record into the result file: the state of the last row written (with its time
// and the row count) and the run's figures (setFigures, by name: runtime/output/run_figures.h),
// at every flush after a row was appended.
class RestartRecordWriter : public OutputSink {
 public:
  // Creates the group `restart` for a state of `state_size` entries, or opens it when the
  // file is opened for a restart; `rows`: the rows already in the file.
  RestartRecordWriter(ResultFile& file, int state_size, long rows);
  void write(const OutputSample& sample) override;
  void flush() override;
  void setFigures(const std::map<std::string, double>& figures) { figures_ = figures; }
  // The record is written again at the next flush (with the figures set since).
  void markPending() { pending_ = rows_ > 0; }
  void abandon() override { group_.release(), state_.release(); }

 private:
  ResultFile& file_;
  h5::Handle group_, state_;
  bool pending_ = false;  // a row was appended since the record was written
  long rows_ = 0;
  double time_ = 0.0, dissipated_ = 0.0;
  Eigen::VectorXd y_;
  std::map<std::string, double> figures_;
};

// Reads the record of a result file; InputError (exit code 2) naming the file if it is not a
// result file of this format version or has no complete record yet.
RestartRecord readRestartRecord(const std::string& path);

}  // namespace ffriga
