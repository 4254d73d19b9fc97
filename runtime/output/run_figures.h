// The figures of a run that the result file records (schemas/result_format.md "Root
// attributes"): status, times, the headline contact figures, CVODE's statistics and the
// phases of paper Table 3; and their names in the restart record, from which a restarted
// run continues them.
#pragma once

#include <map>
#include <string>

#include "runtime/output/result_file.h"

namespace ffriga {

// Wall time (s), steps and right-hand sides (all kinds) of one phase of the run.
struct PhaseFigures {
  double wall_s = 0.0;
  long steps = 0;
  long rhs_evals = 0;
};

// CVODE's counters (runtime/integration/bdf_integrator.h IntegratorStats).
struct SolverCounts {
  long steps = 0;
  long rhs_evals = 0;  // excluding those of difference-quotient Jacobians
  long jacobian_evals = 0;
  long jacobian_rhs_evals = 0;
  long linear_setups = 0;
  long error_test_failures = 0;
  long nonlinear_iterations = 0;
  long convergence_failures = 0;
};

struct RunFigures {
  std::string status;       // "completed", "interrupted by ...", "failed at ..."
  double final_time = 0.0;  // s
  double wall_time_s = 0.0;
  double max_contact_force = 0.0;        // N, over the steps and contact pairs
  double max_contact_force_time = -1.0;  // s, the end of its step (-1: no contact)
  // The first contact (any pair; a body bouncing or a chain of balls has several): the
  // midpoints of the steps in which it began and ended (-1: none, or not ended). A first
  // contact whose force stays below 1 % of a later one's is a touch on the way in: the
  // later contact continues it (runtime/simulation/simulation.cc trackFirstContact).
  double contact_begin = -1.0;  // s
  double contact_end = -1.0;    // s
  double first_contact_peak = 0.0;  // N, the largest force of the first contact so far
  double contact_run_peak = 0.0;    // N, that of the latest run of steps in contact
  long contact_events = 0;      // contacts begun: steps in contact after steps without
  SolverCounts solver;
  PhaseFigures before, during, after;  // before, during and after contact (Table 3)
  long long contact_searches = 0;          // closest-point searches in this invocation
  long long contact_searches_avoided = 0;  // and those the clearance bound spared
};

// The root attributes status, final_time_s, wall_time_s, the headline figures, solver_*,
// contact_point_searches* and phase_*.
void writeRunFigures(ResultFile& file, const RunFigures& figures);

// The figures a restart needs to continue the run, by name (the restart record's
// figure_* attributes), with the contact phase (0 before, 1 during, 2 after) and the wall
// time so far (s); and back.
std::map<std::string, double> restartFigures(const RunFigures& figures, int phase, double wall);
void restoreFigures(const std::map<std::string, double>& record, RunFigures& figures, int& phase,
                    double& wall);

}  // namespace ffriga
