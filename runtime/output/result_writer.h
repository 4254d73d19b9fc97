// The outputs of one run (schemas/result_format.md): the result file and its sinks
// (runtime/output/output_sink.h): the rows, the sensors, the restart record, the contact
// pressure at each pair's force peak and, when asked for, the visualisation frames and the
// stresses along lines at the force peak.
//
// The file grows as the run goes: every sample becomes one row of every series; the file is
// flushed every `flush_rows` rows, at least every `flush_interval` seconds of wall time
// (flushIfDue, called after every step) and on close. Between flushes nothing is written to
// the file, so a run that fails, is interrupted or even killed (SIGKILL) leaves a readable
// file with every row older than the flush interval, and the root attribute `status` saying
// why it stopped ("running" if it was killed).
#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "runtime/output/output_sample.h"
#include "runtime/output/output_sink.h"
#include "runtime/output/peak_contact_pressure.h"
#include "runtime/output/peak_stress_lines.h"
#include "runtime/output/restart_record.h"
#include "runtime/output/result_file.h"
#include "runtime/output/visualisation_frames.h"

namespace ffriga {

// When the result file is flushed (scene keys outputs.flush_rows, outputs.flush_interval).
struct FlushConfig {
  int rows = 16;          // every this many rows
  double interval = 2.0;  // s of wall time, at least, while rows are pending
};

class ResultWriter {
 public:
  // Creates (truncates) `path`; writes the root attributes format, format_version,
  // created_by, scene_yaml and status = "running", and the rows, sensors and restart record
  // of `layout`. With `resume` (a restart, runtime/output/restart_record.h): opens the
  // existing file instead, checks that its layout is this one, and drops every row after
  // resume->rows.
  ResultWriter(const std::string& path, const OutputLayout& layout, const std::string& created_by,
               const std::string& scene_yaml, const FlushConfig& flush_config,
               const RestartRecord* resume = nullptr);
  ~ResultWriter();

  // Visualisation frames (runtime/output/visualisation_frames.h) from now on, at the output
  // rows they fall on; on a restart, frames after the restart time are dropped.
  void enableFrames(const VisualisationFramesConfig& settings);
  // Stresses along the SIDs' stress lines at the largest contact force
  // (runtime/output/peak_stress_lines.h); partners: each body's Hertz partner, if any.
  void enablePeakStressLines(std::vector<std::optional<HertzPartner>> partners);
  // Whether recordPeak is wanted.
  bool wantsPeaks() const { return peaks_ != nullptr; }
  // A step ending at t has the largest contact force so far (N); the bodies' state there.
  void recordPeak(double t, double force, const std::vector<BodySample>& bodies);
  // The largest normal force of contact pair c recorded so far (N; 0 before any, kept over a
  // restart) and pair c's pressure field at a step with a larger one
  // (runtime/output/peak_contact_pressure.h).
  double pressurePeakForce(int c) const { return pressure_ ? pressure_->peakForce(c) : 0.0; }
  void recordPressurePeak(int c, double t, double force, const PressureSample& field);
  // One output row.
  void append(const OutputSample& sample);
  // Writes the pending rows and flushes the file. First reserves their room on disk: if the
  // disk or the file size limit has none, ComputeError, and the file keeps the rows of the
  // last flush (no later flush is tried; close() still writes the status). A write that
  // fails anyway marks the file broken (runtime/output/result_file.h).
  void flush();
  // Every object of the run exists (after enableFrames and enablePeakStressLines): the file
  // goes into SWMR mode, readable while it grows (schemas/result_format.md).
  void startSwmr();
  // Flushes if rows are pending and the last flush is flush_interval or more seconds ago.
  void flushIfDue();
  // The run's figures so far (runtime/output/run_figures.h restartFigures): written to the
  // restart record at the next flush, with the state of the last appended row.
  void setRunFigures(const std::map<std::string, double>& figures) {
    if (restart_) restart_->setFigures(figures);
  }
  long rows() const { return rows_; }
  long frames() const { return frames_ ? frames_->frames() : frames_written_; }
  // The stress lines' maxima at the force peak recorded in this run (kept after close).
  std::vector<StressLinePeak> stressLinePeaks() const {
    return peaks_ ? peaks_->peaks() : peak_list_;
  }
  // The file, for the root and group attributes (runtime/output/run_attributes.h).
  ResultFile& file() { return *file_; }
  // Flushes and closes; later calls do nothing.
  void close();

 private:
  OutputLayout layout_;
  std::unique_ptr<ResultFile> file_;
  std::vector<std::unique_ptr<OutputSink>> sinks_;  // in flush order
  RestartRecordWriter* restart_ = nullptr;
  FrameWriter* frames_ = nullptr;
  PeakStressLines* peaks_ = nullptr;
  PeakContactPressure* pressure_ = nullptr;
  double restart_time_ = -1.0;  // the record's time when opened for a restart
  long rows_ = 0;
  long frames_written_ = 0;
  bool refused_ = false;  // a flush found no room: the rows after the last flush stay in memory
  std::vector<StressLinePeak> peak_list_;
  FlushConfig flush_;
  std::chrono::steady_clock::time_point last_flush_;
};

}  // namespace ffriga
