#include "runtime/output/run_figures.h"

#include <cmath>

namespace ffriga {

namespace {

const char* const kPhaseNames[3] = {"before_contact", "during_contact", "after_contact"};

}  // namespace

void writeRunFigures(ResultFile& w, const RunFigures& r) {
  w.setAttribute("status", r.status);
  w.setAttribute("final_time_s", r.final_time);
  w.setAttribute("wall_time_s", r.wall_time_s);
  // Headline figures (schemas/result_format.md): -1 where there was no contact.
  w.setAttribute("max_contact_force_N", r.max_contact_force);
  w.setAttribute("max_contact_force_time_s", r.max_contact_force_time);
  w.setAttribute("contact_begin_s", r.contact_begin);
  w.setAttribute("contact_end_s", r.contact_end);
  w.setAttribute("contact_duration_s", r.contact_begin >= 0.0 && r.contact_end >= 0.0
                                           ? r.contact_end - r.contact_begin
                                           : -1.0);
  w.setAttribute("contact_events", r.contact_events);
  w.setAttribute("solver_steps", r.solver.steps);
  w.setAttribute("solver_rhs_evals", r.solver.rhs_evals);
  w.setAttribute("solver_jacobian_evals", r.solver.jacobian_evals);
  w.setAttribute("solver_jacobian_rhs_evals", r.solver.jacobian_rhs_evals);
  w.setAttribute("solver_linear_setups", r.solver.linear_setups);
  w.setAttribute("solver_error_test_failures", r.solver.error_test_failures);
  w.setAttribute("solver_nonlinear_iterations", r.solver.nonlinear_iterations);
  w.setAttribute("solver_convergence_failures", r.solver.convergence_failures);
  w.setAttribute("contact_point_searches", static_cast<long>(r.contact_searches));
  w.setAttribute("contact_point_searches_avoided", static_cast<long>(r.contact_searches_avoided));
  const PhaseFigures* phases[3] = {&r.before, &r.during, &r.after};
  for (int i = 0; i < 3; ++i) {
    w.setAttribute(std::string("phase_") + kPhaseNames[i] + "_wall_s", phases[i]->wall_s);
    w.setAttribute(std::string("phase_") + kPhaseNames[i] + "_steps", phases[i]->steps);
    w.setAttribute(std::string("phase_") + kPhaseNames[i] + "_rhs_evals", phases[i]->rhs_evals);
  }
}

std::map<std::string, double> restartFigures(const RunFigures& r, int phase, double wall) {
  std::map<std::string, double> f = {
      {"phase", phase},
      {"wall_time_s", wall},
      {"max_contact_force_N", r.max_contact_force},
      {"max_contact_force_time_s", r.max_contact_force_time},
      {"contact_begin_s", r.contact_begin},
      {"contact_end_s", r.contact_end},
      {"first_contact_peak_N", r.first_contact_peak},
      {"contact_run_peak_N", r.contact_run_peak},
      {"contact_events", static_cast<double>(r.contact_events)},
      {"steps", static_cast<double>(r.solver.steps)},
      {"rhs_evals", static_cast<double>(r.solver.rhs_evals)},
      {"jacobian_evals", static_cast<double>(r.solver.jacobian_evals)},
      {"jacobian_rhs_evals", static_cast<double>(r.solver.jacobian_rhs_evals)},
      {"linear_setups", static_cast<double>(r.solver.linear_setups)},
      {"error_test_failures", static_cast<double>(r.solver.error_test_failures)},
      {"nonlinear_iterations", static_cast<double>(r.solver.nonlinear_iterations)},
      {"convergence_failures", static_cast<double>(r.solver.convergence_failures)}};
  const PhaseFigures* phases[3] = {&r.before, &r.during, &r.after};
  for (int i = 0; i < 3; ++i) {
    f[std::string(kPhaseNames[i]) + "_wall_s"] = phases[i]->wall_s;
    f[std::string(kPhaseNames[i]) + "_steps"] = static_cast<double>(phases[i]->steps);
    f[std::string(kPhaseNames[i]) + "_rhs_evals"] = static_cast<double>(phases[i]->rhs_evals);
  }
  return f;
}

void restoreFigures(const std::map<std::string, double>& record, RunFigures& r, int& phase,
                    double& wall) {
  auto get = [&](const std::string& name) {
    const auto it = record.find(name);
    return it == record.end() ? 0.0 : it->second;
  };
  auto getOr = [&](const std::string& name, double fallback) {
    return record.count(name) ? get(name) : fallback;
  };
  auto count = [&](const std::string& name) { return std::lround(get(name)); };
  phase = static_cast<int>(count("phase"));
  wall = get("wall_time_s");
  r.max_contact_force = get("max_contact_force_N");
  r.max_contact_force_time = getOr("max_contact_force_time_s", -1.0);
  r.contact_begin = getOr("contact_begin_s", -1.0);
  r.contact_end = getOr("contact_end_s", -1.0);
  r.first_contact_peak = get("first_contact_peak_N");
  r.contact_run_peak = get("contact_run_peak_N");
  r.contact_events = count("contact_events");
  r.solver.steps = count("steps");
  r.solver.rhs_evals = count("rhs_evals");
  r.solver.jacobian_evals = count("jacobian_evals");
  r.solver.jacobian_rhs_evals = count("jacobian_rhs_evals");
  r.solver.linear_setups = count("linear_setups");
  r.solver.error_test_failures = count("error_test_failures");
  r.solver.nonlinear_iterations = count("nonlinear_iterations");
  r.solver.convergence_failures = count("convergence_failures");
  PhaseFigures* phases[3] = {&r.before, &r.during, &r.after};
  for (int i = 0; i < 3; ++i) {
    phases[i]->wall_s = get(std::string(kPhaseNames[i]) + "_wall_s");
    phases[i]->steps = count(std::string(kPhaseNames[i]) + "_steps");
    phases[i]->rhs_evals = count(std::string(kPhaseNames[i]) + "_rhs_evals");
  }
}

}  // namespace ffriga
