// The time loop of ffrsim: integrates a MultibodySystem with the BDF integrator, writes an
// output row at every multiple of the output interval (interpolated, CVodeGetDky, so outputs
// never shorten the steps), flushes the result file by rows and by wall time, reports
// progress on stderr, honours a stop request (SIGINT, SIGTERM, SIGHUP:
// runtime/simulation/interrupt.h) between steps, and measures the phases of paper Table 3: wall
// time, steps and right-hand sides before the first contact, during contact and after it.
//
// The result file always ends with the root attribute `status`: "completed",
// "interrupted by SIGTERM at t = ... s" or "failed at t = ... s: MESSAGE"; with wall_time_s
// (time integration only) and the solver statistics.
#pragma once

#include <string>

#include <Eigen/Dense>

#include "runtime/integration/bdf_integrator.h"
#include "runtime/output/result_writer.h"
#include "runtime/output/run_figures.h"
#include "runtime/simulation/interrupt.h"
#include "runtime/system/multibody_system.h"

namespace ffriga {

struct SimulationConfig {
  double end_time = 0.0;         // s
  double output_interval = 0.0;  // s; the first row is at t = 0
  // s; > 0: also a row at every multiple of it in steps that begin or end in contact
  double contact_output_interval = 0.0;
  IntegratorOptions integrator;
  int verbosity = 1;               // 0: silent; >= 1: progress on stderr
  double progress_interval = 1.0;  // s of wall time between progress lines
};

// The run's figures (runtime/output/run_figures.h) and how it ended.
struct SimulationReport {
  RunFigures figures;  // status, times, headline figures, solver counts, phases
  bool completed = false;
  bool interrupted = false;
};

// Runs from (0, y0) to settings.end_time. Integration failures are recorded in the file and
// the report (completed = false) and rethrown as ComputeError after the file is closed.
// With `resume` (a restart): from (resume->time, y0 = resume->state) instead, the report's
// figures and statistics continued from the record, no row written at the start (the
// writer was opened on the record's file).
SimulationReport simulate(MultibodySystem& system, const Eigen::VectorXd& y0,
                          const SimulationConfig& settings, ResultWriter& writer,
                          const RestartRecord* resume = nullptr);

}  // namespace ffriga
