#include "runtime/simulation/simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "common/base/error.h"

namespace ffriga {

namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

void countSearches(const MultibodySystem& system, SimulationReport& r) {
  r.contact_searches = r.contact_searches_avoided = 0;
  for (int c = 0; c < system.numContacts(); ++c) {
    r.contact_searches += system.contact(c).searches();
    r.contact_searches_avoided += system.contact(c).searchesAvoided();
  }
}

void writeStatistics(ResultWriter& w, const SimulationReport& r) {
  w.setAttribute("status", r.status);
  w.setAttribute("final_time_s", r.final_time);
  w.setAttribute("wall_time_s", r.wall_time_s);
  // Headline figures (schemas/result_format.md): -1 where there was no contact.
  w.setAttribute("max_contact_force_N", r.max_normal_force);
  w.setAttribute("max_contact_force_time_s", r.max_force_time);
  w.setAttribute("contact_begin_s", r.contact_begin);
  w.setAttribute("contact_end_s", r.contact_end);
  w.setAttribute("contact_duration_s", r.contact_begin >= 0.0 && r.contact_end >= 0.0
                                           ? r.contact_end - r.contact_begin
                                           : -1.0);
  w.setAttribute("solver_steps", r.stats.steps);
  w.setAttribute("solver_rhs_evals", r.stats.rhs_evals);
  w.setAttribute("solver_jacobian_evals", r.stats.jacobian_evals);
  w.setAttribute("solver_jacobian_rhs_evals", r.stats.jacobian_rhs_evals);
  w.setAttribute("solver_linear_setups", r.stats.linear_setups);
  w.setAttribute("solver_error_test_failures", r.stats.error_test_failures);
  w.setAttribute("solver_nonlinear_iterations", r.stats.nonlinear_iterations);
  w.setAttribute("solver_convergence_failures", r.stats.convergence_failures);
  w.setAttribute("contact_point_searches", static_cast<long>(r.contact_searches));
  w.setAttribute("contact_point_searches_avoided", static_cast<long>(r.contact_searches_avoided));
  const PhaseStats* phases[3] = {&r.before, &r.during, &r.after};
  const char* names[3] = {"before_contact", "during_contact", "after_contact"};
  for (int i = 0; i < 3; ++i) {
    w.setAttribute(std::string("phase_") + names[i] + "_wall_s", phases[i]->wall_s);
    w.setAttribute(std::string("phase_") + names[i] + "_steps", phases[i]->steps);
    w.setAttribute(std::string("phase_") + names[i] + "_rhs_evals", phases[i]->rhs_evals);
  }
}

// The step limit of the approach control (simulate()). It acts through CVODE's stop time,
// which CVODE honours in the very next step (a new maximum step only takes effect at its
// next step size choice: seen stepping 2 ms over a 0.2 ms limit and through the contact).
class ApproachControl {
 public:
  ApproachControl(MultibodySystem& system, double end_time) : system_(system), end_(end_time) {}
  bool active() const { return system_.numContacts() > 0; }
  void update(BdfIntegrator& integ, double t) {
    double size = 0.0;
    const double gap = system_.contactGap(integ.currentState().data(), &size);
    double limit = 0.0;     // none
    bool touching = false;  // in contact: CVODE's own steps resolve it
    for (const ContactState& c : system_.lastRhsContacts())
      touching = touching || c.active_points > 0;
    if (have_ && t > t_ && !touching) {
      const double speed = (gap_ - gap) / (t - t_);
      if (speed > 0.0) limit = gap > 0.0 ? 0.5 * gap / speed : 0.01 * size / speed;
    }
    const double stop = limit > 0.0 ? std::min(end_, t + limit) : end_;
    if (stop != stop_ && stop > t) {
      integ.setStopTime(stop);
      stop_ = stop;
    }
    gap_ = gap, t_ = t, have_ = true;
  }

 private:
  MultibodySystem& system_;
  double end_;
  double gap_ = 0.0, t_ = 0.0, stop_ = -1.0;
  bool have_ = false;
};

// A penetration the contact surfaces cannot represent (ContactState::beyond_edge_penetration)
// or a point near the other surface whose closest point could not be found stops the run:
// its force would be missing, and the result would look fine.
void checkRepresentable(const MultibodySystem& system, double t) {
  const std::vector<ContactState>& states = system.lastRhsContacts();
  for (int c = 0; c < static_cast<int>(states.size()); ++c) {
    const ContactPair& pair = system.contact(c);
    if (states[c].projection_failures > 0) {
      throw ComputeError(Str() << "contact '" << pair.name() << "': at t = " << t << " s the "
                               << "closest-point search (Eq. 15) failed for "
                               << states[c].projection_failures << " collocation point(s) near "
                               << "the other surface (bodies '" << system.body(pair.bodyA()).name()
                               << "' and '" << system.body(pair.bodyB()).name() << "'): their "
                               << "contact forces cannot be computed");
    }
    if (states[c].beyond_edge_penetration <= pair.penetrationTolerance()) continue;
    throw ComputeError(Str() << "contact '" << pair.name() << "': at t = " << t << " s a point "
                             << "penetrates by " << states[c].beyond_edge_penetration
                             << " m beyond the edge of a contact surface (bodies '"
                             << system.body(pair.bodyA()).name() << "' and '"
                             << system.body(pair.bodyB()).name() << "'), where it gets no force: "
                             << "the contact region is too small for this motion (enlarge "
                             << "contact.region in the body file)");
  }
}

IntegratorStats sumOf(const IntegratorStats& a, const IntegratorStats& b) {
  IntegratorStats s = b;
  s.steps += a.steps;
  s.rhs_evals += a.rhs_evals;
  s.jacobian_evals += a.jacobian_evals;
  s.jacobian_rhs_evals += a.jacobian_rhs_evals;
  s.linear_setups += a.linear_setups;
  s.error_test_failures += a.error_test_failures;
  s.nonlinear_iterations += a.nonlinear_iterations;
  s.convergence_failures += a.convergence_failures;
  return s;
}

// The figures a restart needs to continue the report (restart record, by name).
std::map<std::string, double> runFigures(const SimulationReport& r, int phase, double wall) {
  std::map<std::string, double> f = {
      {"phase", phase},
      {"wall_time_s", wall},
      {"max_contact_force_N", r.max_normal_force},
      {"max_contact_force_time_s", r.max_force_time},
      {"contact_begin_s", r.contact_begin},
      {"contact_end_s", r.contact_end},
      {"steps", static_cast<double>(r.stats.steps)},
      {"rhs_evals", static_cast<double>(r.stats.rhs_evals)},
      {"jacobian_evals", static_cast<double>(r.stats.jacobian_evals)},
      {"jacobian_rhs_evals", static_cast<double>(r.stats.jacobian_rhs_evals)},
      {"linear_setups", static_cast<double>(r.stats.linear_setups)},
      {"error_test_failures", static_cast<double>(r.stats.error_test_failures)},
      {"nonlinear_iterations", static_cast<double>(r.stats.nonlinear_iterations)},
      {"convergence_failures", static_cast<double>(r.stats.convergence_failures)}};
  const PhaseStats* phases[3] = {&r.before, &r.during, &r.after};
  const char* names[3] = {"before_contact", "during_contact", "after_contact"};
  for (int i = 0; i < 3; ++i) {
    f[std::string(names[i]) + "_wall_s"] = phases[i]->wall_s;
    f[std::string(names[i]) + "_steps"] = static_cast<double>(phases[i]->steps);
    f[std::string(names[i]) + "_rhs_evals"] = static_cast<double>(phases[i]->rhs_evals);
  }
  return f;
}

void restoreFigures(const RestartRecord& rec, SimulationReport& r, int& phase,
                    IntegratorStats& stats, double& wall) {
  auto get = [&](const std::string& name) {
    const auto it = rec.figures.find(name);
    return it == rec.figures.end() ? 0.0 : it->second;
  };
  auto count = [&](const std::string& name) { return std::lround(get(name)); };
  phase = static_cast<int>(count("phase"));
  wall = get("wall_time_s");
  r.max_normal_force = get("max_contact_force_N");
  r.max_force_time =
      rec.figures.count("max_contact_force_time_s") ? get("max_contact_force_time_s") : -1.0;
  r.contact_begin = rec.figures.count("contact_begin_s") ? get("contact_begin_s") : -1.0;
  r.contact_end = rec.figures.count("contact_end_s") ? get("contact_end_s") : -1.0;
  stats.steps = count("steps");
  stats.rhs_evals = count("rhs_evals");
  stats.jacobian_evals = count("jacobian_evals");
  stats.jacobian_rhs_evals = count("jacobian_rhs_evals");
  stats.linear_setups = count("linear_setups");
  stats.error_test_failures = count("error_test_failures");
  stats.nonlinear_iterations = count("nonlinear_iterations");
  stats.convergence_failures = count("convergence_failures");
  PhaseStats* phases[3] = {&r.before, &r.during, &r.after};
  const char* names[3] = {"before_contact", "during_contact", "after_contact"};
  for (int i = 0; i < 3; ++i) {
    phases[i]->wall_s = get(std::string(names[i]) + "_wall_s");
    phases[i]->steps = count(std::string(names[i]) + "_steps");
    phases[i]->rhs_evals = count(std::string(names[i]) + "_rhs_evals");
  }
  r.stats = stats;
}

// Phase bookkeeping (paper Table 3): whether the bodies touch at the end of the step, as
// the step's last right-hand side saw it (MultibodySystem::lastRhsContacts, the Hertz point
// contacts' forces); the largest force so far goes into the report.
bool contactAtStepEnd(const MultibodySystem& system, SimulationReport& report) {
  bool contact = false;
  for (const ContactState& s : system.lastRhsContacts()) {
    contact = contact || s.active_points > 0;
    report.max_normal_force = std::max(report.max_normal_force, s.normal_force);
  }
  for (int f = 0; f < system.numLineForces(); ++f) {
    if (!system.lineForce(f).isContact()) continue;
    const double force = -system.lastRhsLineForces()[f].tension;
    contact = contact || force > 0.0;
    report.max_normal_force = std::max(report.max_normal_force, force);
  }
  return contact;
}

// In a step (tPrev, t] that begins or ends in contact, also every multiple of the contact
// output interval dtc (> 0) that is not a regular output already; `times` stays sorted.
void addContactOutputs(double dtc, bool in_contact, double tPrev, double t,
                       std::vector<double>& times) {
  if (!(dtc > 0.0) || !in_contact) return;
  for (long k = static_cast<long>(std::floor(tPrev / dtc)) + 1; k * dtc <= t; ++k) {
    bool regular = false;
    for (double r : times) regular = regular || std::abs(r - k * dtc) <= 1e-9 * dtc;
    if (k * dtc > tPrev && !regular) times.push_back(k * dtc);
  }
  std::sort(times.begin(), times.end());
}

// The output rows inside the last step, by interpolation (CVodeGetDky); y is scratch.
void writeOutputs(BdfIntegrator& integ, MultibodySystem& system, ResultWriter& writer,
                  const std::vector<double>& times, double t, Eigen::VectorXd& y) {
  for (const double to : times) {
    integ.interpolate(std::min(to, t), y);
    // The interpolant leaves the constraint manifold by about the local error: an output
    // row is projected onto it like every step's state.
    if (system.hasConstraints() && !system.projectState(y.data())) {
      throw ComputeError(Str() << "projecting the output at t = " << to << " s onto the joints' "
                               << "constraints and the quasi-static manifold did not converge");
    }
    system.normalize(y.data());
    writer.append(to, y, system);
  }
}

void printProgress(const SimulationSettings& settings, double t, const IntegratorStats& now,
                   double elapsed) {
  const double left = t > 0.0 ? elapsed * (settings.end_time - t) / t : 0.0;
  std::fprintf(stderr, "ffrsim: t = %.6g s (%.1f %%), %ld steps, %.1f s elapsed, ~%.1f s left\n",
               t, 100.0 * t / settings.end_time, now.steps, elapsed, left);
  if (settings.verbosity > 1) {
    std::fprintf(stderr,
                 "ffrsim:   step %.3g s, order %d, %ld error-test and %ld convergence failures, "
                 "%ld Jacobians, %ld Newton iterations\n",
                 now.last_step, now.last_order, now.error_test_failures, now.convergence_failures,
                 now.jacobian_evals, now.nonlinear_iterations);
  }
}

}  // namespace

SimulationReport simulate(MultibodySystem& system, const Eigen::VectorXd& y0,
                          const SimulationSettings& settings, ResultWriter& writer,
                          const RestartRecord* resume) {
  FFRIGA_CHECK(
      settings.end_time > 0.0 && settings.output_interval > 0.0,
      "end time " << settings.end_time << ", output interval " << settings.output_interval);
  SimulationReport report;
  const Clock::time_point start = Clock::now();
  Eigen::VectorXd y = y0;
  system.normalize(y.data());
  const long nOut =
      std::max(1L, std::lround(std::ceil(settings.end_time / settings.output_interval - 1e-9)));
  long nextOut = 1;
  auto outputTime = [&](long k) {
    return std::min(settings.end_time, k * settings.output_interval);
  };
  int phase = 0;  // 0 before contact, 1 during, 2 after
  double t = 0.0;
  IntegratorStats before;  // of the parts of the run before a restart
  double wallBefore = 0.0;
  if (resume) {
    t = resume->time;
    restoreFigures(*resume, report, phase, before, wallBefore);
    // The next regular output strictly after the record's row.
    nextOut = static_cast<long>(std::floor(t / settings.output_interval * (1.0 + 1e-12))) + 1;
  } else {
    writer.append(0.0, y, system);
  }
  Clock::time_point lastProgress = start;
  try {
    BdfIntegrator integ(system, t, y, settings.integrator);
    integ.setStopTime(settings.end_time);
    IntegratorStats last;
    double tPrev = t;
    // Approach control: bodies that swing into contact from afar must not step over it. With
    // the contact pairs' box gap d and its closing speed s (from the last two steps), the
    // step is limited to d / (2 s) while the boxes are apart, and to the time in which the
    // surfaces move by 1 % of the contact surface's size once they overlap, until a contact
    // point is active (then CVODE's own steps resolve the contact). Without pairs: nothing.
    ApproachControl approach(system, settings.end_time);
    while (t < settings.end_time && nextOut <= nOut) {
      if (interruptRequested()) {
        report.interrupted = true;
        break;
      }
      const Clock::time_point s0 = Clock::now();
      if (approach.active()) approach.update(integ, t);
      t = integ.step();
      const double maxBefore = report.max_normal_force;
      const bool contact = contactAtStepEnd(system, report);
      if (report.max_normal_force > maxBefore) {
        report.max_force_time = t;
        writer.recordPeak(t, report.max_normal_force, integ.currentState(), system);
      }
      checkRepresentable(system, t);
      std::vector<double> times;  // the regular outputs inside this step
      while (nextOut <= nOut && outputTime(nextOut) <= t * (1.0 + 1e-14))
        times.push_back(outputTime(nextOut++));
      addContactOutputs(settings.contact_output_interval, contact || phase == 1, tPrev, t, times);
      writeOutputs(integ, system, writer, times, t, y);
      if (contact && report.contact_begin < 0.0) report.contact_begin = 0.5 * (tPrev + t);
      if (!contact && phase == 1) report.contact_end = 0.5 * (tPrev + t);
      if (contact)
        phase = 1;
      else if (phase == 1)
        phase = 2;
      tPrev = t;
      writer.flushIfDue();
      const IntegratorStats now = integ.stats();
      PhaseStats& ps = phase == 0 ? report.before : phase == 1 ? report.during : report.after;
      const Clock::time_point s1 = Clock::now();
      ps.wall_s += seconds(s0, s1);
      ps.steps += now.steps - last.steps;
      ps.rhs_evals +=
          (now.rhs_evals + now.jacobian_rhs_evals) - (last.rhs_evals + last.jacobian_rhs_evals);
      last = now;
      report.stats = sumOf(before, now);
      writer.setRunFigures(runFigures(report, phase, wallBefore + seconds(start, s1)));
      if (settings.verbosity > 0 && seconds(lastProgress, s1) >= settings.progress_interval) {
        lastProgress = s1;
        printProgress(settings, t, now, seconds(start, s1));
      }
    }
    report.final_time = t;
    report.wall_time_s = wallBefore + seconds(start, Clock::now());
    if (report.interrupted) {
      report.status = Str() << "interrupted by " << interruptSignalName() << " at t = " << t << " s";
    } else {
      report.completed = true;
      report.status = "completed";
    }
    countSearches(system, report);
    writeStatistics(writer, report);
    writer.flush();
  } catch (const std::exception& e) {
    report.final_time = t;
    report.wall_time_s = wallBefore + seconds(start, Clock::now());
    report.status = Str() << "failed at t = " << t << " s: " << e.what();
    countSearches(system, report);
    writeStatistics(writer, report);
    writer.close();
    throw ComputeError(report.status);
  }
  return report;
}

}  // namespace ffriga
