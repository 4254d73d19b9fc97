#include "runtime/simulation/simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "common/base/error.h"
#include "runtime/simulation/output_sampler.h"

namespace ffriga {

namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

void countSearches(const MultibodySystem& system, RunFigures& r) {
  r.contact_searches = r.contact_searches_avoided = 0;
  for (int c = 0; c < system.numContacts(); ++c) {
    r.contact_searches += system.contact(c).searches();
    r.contact_searches_avoided += system.contact(c).searchesAvoided();
  }
}

// The counters of the parts of a run before a restart (`before`) plus this part's.
SolverCounts sumOf(const SolverCounts& before, const IntegratorStats& now) {
  SolverCounts s = before;
  s.steps += now.steps;
  s.rhs_evals += now.rhs_evals;
  s.jacobian_evals += now.jacobian_evals;
  s.jacobian_rhs_evals += now.jacobian_rhs_evals;
  s.linear_setups += now.linear_setups;
  s.error_test_failures += now.error_test_failures;
  s.nonlinear_iterations += now.nonlinear_iterations;
  s.convergence_failures += now.convergence_failures;
  return s;
}

// The step limit of the approach control (TimeLoop). It acts through CVODE's stop time,
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
    const SurfaceContact& pair = system.contact(c);
    const std::string& nameA = system.contactSideName(c, 0);
    const std::string& nameB = system.contactSideName(c, 1);
    if (states[c].projection_failures > 0) {
      throw ComputeError(Str() << "contact '" << pair.name() << "': at t = " << t << " s the "
                               << "closest-point search (Eq. 15) failed for "
                               << states[c].projection_failures << " collocation point(s) near "
                               << "the other surface ('" << nameA << "' and '" << nameB
                               << "'): their "
                               << "contact forces cannot be computed");
    }
    if (states[c].beyond_edge_penetration <= pair.penetrationTolerance()) continue;
    throw ComputeError(Str() << "contact '" << pair.name() << "': at t = " << t << " s a point "
                             << "penetrates by " << states[c].beyond_edge_penetration
                             << " m beyond the edge of a contact surface ('" << nameA << "' and '"
                             << nameB << "'), where it gets no force: "
                             << "the contact region is too small for this motion (enlarge "
                             << "contact.region in the body file)");
  }
}

// Phase bookkeeping (paper Table 3): whether the bodies touch at the end of the step, as
// the step's last right-hand side saw it (MultibodySystem::lastRhsContacts, the Hertz point
// contacts' forces); the step's largest force into stepForce, the largest so far into the
// figures.
bool contactAtStepEnd(const MultibodySystem& system, RunFigures& figures, double& stepForce) {
  bool contact = false;
  stepForce = 0.0;
  for (const ContactState& s : system.lastRhsContacts()) {
    contact = contact || s.active_points > 0;
    stepForce = std::max(stepForce, s.normal_force);
  }
  for (int f = 0; f < system.numLineForces(); ++f) {
    if (!system.lineForce(f).isContact()) continue;
    const double force = -system.lastRhsLineForces()[f].tension;
    contact = contact || force > 0.0;
    stepForce = std::max(stepForce, force);
  }
  figures.max_contact_force = std::max(figures.max_contact_force, stepForce);
  return contact;
}

// The first contact's begin and end (RunFigures) after a step with or without contact
// (`contact`, the step's largest contact force `stepForce`), `phase` the contact phase
// before the step. A first contact whose force stayed below kTouch of a later one's was a
// touch on the way in (seen: a quasi-static sphere's first collocation point, released for
// 0.01 us as the surface gave way, 95 us before the end of the impact): that later contact
// then continues the first, whose end is reopened.
void trackFirstContact(bool contact, double stepForce, int phase, double tPrev, double t,
                       RunFigures& f) {
  constexpr double kTouch = 1e-2;
  if (contact && phase != 1) f.contact_run_peak = 0.0;  // a new run of contact steps
  if (contact) f.contact_run_peak = std::max(f.contact_run_peak, stepForce);
  if (contact && f.contact_begin < 0.0) f.contact_begin = 0.5 * (tPrev + t);
  if (contact && f.contact_end >= 0.0 && f.first_contact_peak < kTouch * f.contact_run_peak)
    f.contact_end = -1.0;
  if (contact && f.contact_end < 0.0)
    f.first_contact_peak = std::max(f.first_contact_peak, f.contact_run_peak);
  if (!contact && phase == 1 && f.contact_end < 0.0) f.contact_end = 0.5 * (tPrev + t);
}

// Each contact pair's pressure field at its own force peak: where the step's last right-hand
// side (whose states the figures read) gave the pair a larger normal force than the one
// recorded, the field of that same evaluation, which the pair kept in its serial sums
// (SurfaceContact::pressureField). Chosen over evaluating the pair again at the peak: that
// costs a closest-point search per point, moves the searches' warm starts and clearance
// records (and so the following steps' bits), and would not be the evaluation whose force
// the figures report. Ordinary steps pay one comparison per pair.
void recordPressurePeaks(const MultibodySystem& system, double t, ResultWriter& writer) {
  const std::vector<ContactState>& states = system.lastRhsContacts();
  for (int c = 0; c < static_cast<int>(states.size()); ++c) {
    if (states[c].normal_force > writer.pressurePeakForce(c))
      writer.recordPressurePeak(c, t, states[c].normal_force, pressureSample(system, c));
  }
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

// The energy (J) modal damping and dampers took out between a and b inside the last step:
// MultibodySystem::dissipationPower on CVODE's interpolant, 3-point Gauss-Legendre. The rule
// is exact to degree 5; the power, quadratic in the interpolated velocities, has degree up
// to 2 k for BDF order k, and the rule's error, O(h^7) per step, stays below the
// integrator's own (test e2e.dissipation: the balance follows rtol).
double dissipatedBetween(const BdfIntegrator& integ, const MultibodySystem& system, double a,
                         double b, Eigen::VectorXd& work) {
  if (!(b > a)) return 0.0;
  static const double x[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
  static const double w[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    integ.interpolate(0.5 * (a + b) + 0.5 * (b - a) * x[i], work);
    sum += w[i] * system.dissipationPower(work.data());
  }
  return 0.5 * (b - a) * sum;
}

// The friction's power (W) of the pairs' states.
double frictionPower(const std::vector<ContactState>& states) {
  double power = 0.0;
  for (const ContactState& s : states) power += s.friction_power;
  return power;
}

// The same at y: the contact pairs evaluated there.
double frictionPower(MultibodySystem& system, const double* y) {
  std::vector<Eigen::VectorXd> h;
  std::vector<ContactState> states;
  system.contactForces(y, h, &states);
  return frictionPower(states);
}

// The output rows at `times` inside the step that ended at t, by interpolation
// (CVodeGetDky); y is scratch; `dissipatedAt` gives /energy/dissipated at a time inside the
// step.
template <class Dissipated>
void writeOutputs(BdfIntegrator& integ, MultibodySystem& system, ResultWriter& writer,
                  const std::vector<double>& times, double t, Eigen::VectorXd& y,
                  const Dissipated& dissipatedAt) {
  for (const double to : times) {
    const double dissipated = dissipatedAt(std::min(to, t));
    integ.interpolate(std::min(to, t), y);
    // The interpolant leaves the constraint manifold by about the local error: an output
    // row is projected onto it like every step's state.
    if (system.hasConstraints() && !system.projectState(y.data())) {
      throw ComputeError(Str() << "projecting the output at t = " << to << " s onto the joints' "
                               << "constraints and the quasi-static manifold did not converge");
    }
    system.normalize(y.data());
    OutputSample sample = outputSample(system, to, y);
    sample.energy.dissipated = dissipated;
    writer.append(sample);
  }
}

void printProgress(const SimulationConfig& settings, double t, const IntegratorStats& now,
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

// One run of the time loop: its output schedule, contact phase and figures.
class TimeLoop {
 public:
  TimeLoop(MultibodySystem& system, const SimulationConfig& settings, ResultWriter& writer)
      : system_(system), settings_(settings), writer_(writer), start_(Clock::now()) {
    nOut_ = std::max(1L, std::lround(std::ceil(settings.end_time / settings.output_interval - 1e-9)));
    last_progress_ = start_;
  }
  // The first row at t = 0, or (a restart) the figures and the output schedule of the record.
  void begin(const Eigen::VectorXd& y, const RestartRecord* resume);
  // Steps until the end time or a stop request.
  void run(Eigen::VectorXd& y);
  // The status and the figures at the end, written to the file.
  SimulationReport finish();
  // A failure: the status and the figures so far, written; the file closed.
  SimulationReport fail(const std::exception& e);

 private:
  double outputTime(long k) const {
    return std::min(settings_.end_time, k * settings_.output_interval);
  }
  void step(BdfIntegrator& integ, ApproachControl& approach, Eigen::VectorXd& y);
  void account(const BdfIntegrator& integ, Clock::time_point s0);

  MultibodySystem& system_;
  const SimulationConfig& settings_;
  ResultWriter& writer_;
  SimulationReport report_;
  Clock::time_point start_, last_progress_;
  long nOut_ = 1, nextOut_ = 1;
  int phase_ = 0;  // 0 before contact, 1 during, 2 after
  double t_ = 0.0, tPrev_ = 0.0;
  SolverCounts before_;  // of the parts of the run before a restart
  // /energy/dissipated at tPrev_ (J); whether anything dissipates at all; with friction,
  // the friction's power at tPrev_ (W).
  double dissipated_ = 0.0;
  bool dissipates_ = false, friction_ = false;
  double frictionPower_ = 0.0;
  Eigen::VectorXd work_;
  double wallBefore_ = 0.0;
  IntegratorStats last_;
};

void TimeLoop::begin(const Eigen::VectorXd& y, const RestartRecord* resume) {
  dissipates_ = system_.dissipates();
  friction_ = system_.hasFriction();
  if (friction_) frictionPower_ = frictionPower(system_, y.data());
  work_.resize(y.size());
  if (resume) {
    t_ = resume->time;
    dissipated_ = resume->dissipated;
    restoreFigures(resume->figures, report_.figures, phase_, wallBefore_);
    before_ = report_.figures.solver;
    // The next regular output strictly after the record's row.
    nextOut_ = static_cast<long>(std::floor(t_ / settings_.output_interval * (1.0 + 1e-12))) + 1;
  } else {
    writer_.append(outputSample(system_, 0.0, y));
  }
  tPrev_ = t_;
}

void TimeLoop::run(Eigen::VectorXd& y) {
  BdfIntegrator integ(system_, t_, y, settings_.integrator);
  integ.setStopTime(settings_.end_time);
  // Approach control: bodies that swing into contact from afar must not step over it. With
  // the contact pairs' box gap d and its closing speed s (from the last two steps), the
  // step is limited to d / (2 s) while the boxes are apart, and to the time in which the
  // surfaces move by 1 % of the contact surface's size once they overlap, until a contact
  // point is active (then CVODE's own steps resolve the contact). Without pairs: nothing.
  ApproachControl approach(system_, settings_.end_time);
  while (t_ < settings_.end_time && nextOut_ <= nOut_) {
    if (interruptRequested()) {
      report_.interrupted = true;
      break;
    }
    step(integ, approach, y);
  }
}

void TimeLoop::step(BdfIntegrator& integ, ApproachControl& approach, Eigen::VectorXd& y) {
  RunFigures& f = report_.figures;
  const Clock::time_point s0 = Clock::now();
  if (approach.active()) approach.update(integ, t_);
  t_ = integ.step();
  const double maxBefore = f.max_contact_force;
  double stepForce = 0.0;
  const bool contact = contactAtStepEnd(system_, f, stepForce);
  if (f.max_contact_force > maxBefore) {
    f.max_contact_force_time = t_;
    if (writer_.wantsPeaks())
      writer_.recordPeak(t_, f.max_contact_force, bodySamples(system_, integ.currentState()));
  }
  recordPressurePeaks(system_, t_, writer_);
  checkRepresentable(system_, t_);
  std::vector<double> times;  // the regular outputs inside this step
  while (nextOut_ <= nOut_ && outputTime(nextOut_) <= t_ * (1.0 + 1e-14))
    times.push_back(outputTime(nextOut_++));
  addContactOutputs(settings_.contact_output_interval, contact || phase_ == 1, tPrev_, t_, times);
  // Friction's work: the trapezoidal rule on its power at the step's ends (the last
  // right-hand side's, at the accepted state), linear inside the step.
  const double frictionEnd = friction_ ? frictionPower(system_.lastRhsContacts()) : 0.0;
  auto dissipatedAt = [&](double to) {
    if (!dissipates_) return 0.0;
    double w = dissipated_ + dissipatedBetween(integ, system_, tPrev_, to, work_);
    if (friction_ && to > tPrev_) {
      const double pTo =
          frictionPower_ + (frictionEnd - frictionPower_) * (to - tPrev_) / (t_ - tPrev_);
      w += 0.5 * (to - tPrev_) * (frictionPower_ + pTo);
    }
    return w;
  };
  writeOutputs(integ, system_, writer_, times, t_, y, dissipatedAt);
  dissipated_ = dissipatedAt(t_);
  frictionPower_ = frictionEnd;
  if (contact && phase_ != 1) ++f.contact_events;
  trackFirstContact(contact, stepForce, phase_, tPrev_, t_, f);
  if (contact)
    phase_ = 1;
  else if (phase_ == 1)
    phase_ = 2;
  tPrev_ = t_;
  writer_.flushIfDue();
  account(integ, s0);
}

// The step's wall time, steps and right-hand sides into its phase; the figures so far to the
// restart record; progress on stderr.
void TimeLoop::account(const BdfIntegrator& integ, Clock::time_point s0) {
  RunFigures& f = report_.figures;
  const IntegratorStats now = integ.stats();
  PhaseFigures& ps = phase_ == 0 ? f.before : phase_ == 1 ? f.during : f.after;
  const Clock::time_point s1 = Clock::now();
  ps.wall_s += seconds(s0, s1);
  ps.steps += now.steps - last_.steps;
  ps.rhs_evals +=
      (now.rhs_evals + now.jacobian_rhs_evals) - (last_.rhs_evals + last_.jacobian_rhs_evals);
  last_ = now;
  f.solver = sumOf(before_, now);
  writer_.setRunFigures(restartFigures(f, phase_, wallBefore_ + seconds(start_, s1)));
  if (settings_.verbosity > 0 && seconds(last_progress_, s1) >= settings_.progress_interval) {
    last_progress_ = s1;
    printProgress(settings_, t_, now, seconds(start_, s1));
  }
}

SimulationReport TimeLoop::finish() {
  RunFigures& f = report_.figures;
  f.final_time = t_;
  f.wall_time_s = wallBefore_ + seconds(start_, Clock::now());
  if (report_.interrupted) {
    f.status = Str() << "interrupted by " << interruptSignalName() << " at t = " << t_ << " s";
  } else {
    report_.completed = true;
    f.status = "completed";
  }
  countSearches(system_, f);
  writeRunFigures(writer_.file(), f);
  writer_.flush();
  return report_;
}

SimulationReport TimeLoop::fail(const std::exception& e) {
  RunFigures& f = report_.figures;
  f.final_time = t_;
  f.wall_time_s = wallBefore_ + seconds(start_, Clock::now());
  f.status = Str() << "failed at t = " << t_ << " s: " << e.what();
  countSearches(system_, f);
  writeRunFigures(writer_.file(), f);
  writer_.close();
  return report_;
}

}  // namespace

SimulationReport simulate(MultibodySystem& system, const Eigen::VectorXd& y0,
                          const SimulationConfig& settings, ResultWriter& writer,
                          const RestartRecord* resume) {
  FFRIGA_CHECK(
      settings.end_time > 0.0 && settings.output_interval > 0.0,
      "end time " << settings.end_time << ", output interval " << settings.output_interval);
  TimeLoop loop(system, settings, writer);
  Eigen::VectorXd y = y0;
  system.normalize(y.data());
  loop.begin(y, resume);
  try {
    loop.run(y);
    return loop.finish();
  } catch (const std::exception& e) {
    throw ComputeError(loop.fail(e).figures.status);
  }
}

}  // namespace ffriga
