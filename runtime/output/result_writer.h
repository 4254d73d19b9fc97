// The result file of ffrsim (HDF5; layout, units and version in schemas/result_format.md).
//
// The file grows as the run goes: every series is a chunked dataset with an unlimited first
// dimension (one row per output time), rows are appended and the file is flushed every
// `flush_rows` rows, at least every `flush_interval` seconds of wall time (flushIfDue, called
// after every step) and on close. Between flushes nothing is written to the file, so a run
// that fails, is interrupted or even killed (SIGKILL) leaves a readable file with every row
// older than the flush interval, and the root attribute `status` saying why it stopped
// ("running" if it was killed).
#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "common/sid/hdf5_io.h"
#include "runtime/output/peak_stress_lines.h"
#include "runtime/output/restart_record.h"
#include "runtime/output/visualisation_frames.h"
#include "runtime/system/multibody_system.h"

namespace ffriga {

constexpr const char* kResultFormat = "ffriga-result";
constexpr int kResultFormatVersion = 4;

class ResultWriter {
 public:
  // Creates (truncates) `path`; writes the root attributes format, format_version,
  // created_by, scene_yaml and status = "running", and the layout of `system`. With
  // `resume` (a restart, runtime/output/restart_record.h): opens the existing file instead,
  // checks that its layout is the one of `system`, and drops every row after resume->rows.
  ResultWriter(const std::string& path, const MultibodySystem& system,
               const std::string& created_by, const std::string& scene_yaml, int flush_rows = 16,
               double flush_interval = 2.0, const RestartRecord* resume = nullptr);
  ~ResultWriter();

  // Visualisation frames (runtime/output/visualisation_frames.h) from now on, at the output
  // rows they fall on; on a restart, frames after the restart time are dropped.
  void enableFrames(const VisualisationSettings& settings, const MultibodySystem& system);
  // Stresses along the SIDs' stress lines at the largest contact force
  // (runtime/output/peak_stress_lines.h); partners: each body's Hertz partner, if any.
  void enablePeakStressLines(const MultibodySystem& system,
                             std::vector<std::optional<HertzPartner>> partners);
  // A step ending at t with state y has the largest contact force so far (N).
  void recordPeak(double t, double force, const Eigen::VectorXd& y, const MultibodySystem& system);
  long frames() const { return frames_ ? frames_->frames() : frames_written_; }
  // The stress lines' maxima at the force peak recorded in this run (kept after close).
  std::vector<StressLinePeak> stressLinePeaks() const { return peak_ ? peak_->peaks() : peaks_; }
  // One output row at time t (s) for state y.
  void append(double t, const Eigen::VectorXd& y, MultibodySystem& system);
  void flush();
  // Flushes if rows are pending and the last flush is flush_interval or more seconds ago.
  void flushIfDue();
  // The run's figures so far (headline figures, statistics): written to the restart record
  // at the next flush, with the state of the last appended row.
  void setRunFigures(const std::map<std::string, double>& figures) { resume_figures_ = figures; }
  long rows() const { return rows_; }
  // Root attributes (replaced if present): status, wall_time_s, solver statistics, ...
  void setAttribute(const std::string& name, const std::string& value);
  void setAttribute(const std::string& name, double value);
  void setAttribute(const std::string& name, long value);
  // Attributes of an object of the file (a group or dataset, by its path, e.g.
  // "/contacts/impact"), replaced if present.
  void setObjectAttribute(const std::string& object, const std::string& name, double value);
  void setObjectAttribute(const std::string& object, const std::string& name,
                          const std::string& value);
  // Flushes and closes; later calls do nothing.
  void close();

 private:
  struct Series {
    h5::Handle dataset;
    int cols = 1;  // 0: one-dimensional (scalar per row)
    bool integer = false;
    std::vector<double> pending;  // rows appended since the last flush, row-major
  };
  Series& create(hid_t group, const std::string& name, int cols, const std::string& unit,
                 const std::string& description, bool integer = false);
  // Rows are kept in memory and written as one block per series at flush() (one HDF5
  // extent and write per series instead of one per row).
  void appendRow(Series& s, const double* row);
  void writePending(Series& s);
  long written_ = 0;  // rows on disk
  h5::Handle group(hid_t parent, const std::string& name);

  std::string path_;
  h5::Handle file_;
  std::vector<std::unique_ptr<Series>> series_;
  Series* time_ = nullptr;
  struct BodySeries {
    Series *position, *orientation, *velocity, *angular_velocity, *q, *qdot;
  };
  std::vector<BodySeries> bodies_;
  struct ContactSeries {
    Series *normal_force, *force, *max_penetration, *active_points, *projection_failures;
  };
  std::vector<ContactSeries> contacts_;
  struct JointSeries {
    Series *force, *moment, *violation;
  };
  std::vector<JointSeries> joints_;
  struct LineForceSeries {
    Series *length, *rate, *tension, *energy;
  };
  std::vector<LineForceSeries> line_forces_;
  struct SensorSeries {
    Series *position, *velocity;
  };
  std::vector<SensorSeries> sensors_;
  Series *kinetic_ = nullptr, *elastic_ = nullptr, *contact_ = nullptr, *gravity_ = nullptr,
         *force_elements_ = nullptr;
  void createMultibodySeries(const MultibodySystem& system);
  void appendMultibodyRows(const Eigen::VectorXd& y, MultibodySystem& system);
  void writeRestartRecord();
  bool appending_ = false;  // opened for a restart: groups and datasets exist
  h5::Handle restart_, restart_state_;
  bool resume_pending_ = false;  // a row was appended since the record was written
  double resume_time_ = 0.0;
  Eigen::VectorXd resume_state_;
  std::map<std::string, double> resume_figures_;
  long rows_ = 0;
  double restart_time_ = -1.0;  // the record's time when opened for a restart
  std::unique_ptr<FrameWriter> frames_;
  std::unique_ptr<PeakStressLines> peak_;
  long frames_written_ = 0;
  std::vector<StressLinePeak> peaks_;
  int flush_rows_ = 16;
  double flush_interval_ = 2.0;  // s of wall time
  std::chrono::steady_clock::time_point last_flush_;
};

}  // namespace ffriga
