#include "runtime/report/run_summary.h"

#include <cstdio>

#include "common/base/version.h"

namespace ffriga {

namespace {

void printSolver(const RunFigures& r) {
  const SolverCounts& s = r.solver;
  std::printf("  simulated %.6g s in %.3f s of wall time\n", r.final_time, r.wall_time_s);
  std::printf(
      "  steps %ld, right-hand sides %ld (+%ld for Jacobians), Jacobians %ld,\n"
      "  Newton iterations %ld, error test failures %ld, convergence failures %ld\n",
      s.steps, s.rhs_evals, s.jacobian_rhs_evals, s.jacobian_evals, s.nonlinear_iterations,
      s.error_test_failures, s.convergence_failures);
  std::printf("  %-16s %10s %8s %10s\n", "phase", "wall [s]", "steps", "rhs");
  const PhaseFigures* p[3] = {&r.before, &r.during, &r.after};
  const char* names[3] = {"before contact", "during contact", "after contact"};
  for (int i = 0; i < 3; ++i)
    std::printf("  %-16s %10.3f %8ld %10ld\n", names[i], p[i]->wall_s, p[i]->steps,
                p[i]->rhs_evals);
}

void printContact(const Scene& scene, const HertzReferences& hertz, const RunFigures& r) {
  bool hertzPoints = false;
  for (int f = 0; f < scene.system->numLineForces(); ++f)
    hertzPoints = hertzPoints || scene.system->lineForce(f).isContact();
  if (scene.system->numContacts() > 0 || hertzPoints) {
    std::printf("  maximum contact force %.6g N (over the steps and pairs)\n", r.max_contact_force);
  }
  if (r.contact_begin >= 0.0) {
    const double end = r.contact_end >= 0.0 ? r.contact_end : r.final_time;
    std::printf("  contact from %.4g us to %.4g us%s: duration %.4g us\n", 1e6 * r.contact_begin,
                1e6 * end, r.contact_end >= 0.0 ? "" : " (still in contact)",
                1e6 * (end - r.contact_begin));
  }
  for (int c = 0; c < scene.system->numContacts(); ++c) {
    const auto& h = hertz[c];
    if (!h) continue;
    std::printf("  Hertz (approach speed %.4g m/s", h->approach_speed);
    if (h->impact.preload != 0.0) std::printf(", weight %.4g N along the normal", h->impact.preload);
    std::printf("): maximum force %.6g N, duration %.4g us\n", h->impact.max_force,
                1e6 * h->impact.duration);
    if (scene.system->numContacts() == 1) {
      const HertzDifference d = differenceFrom(*h, r);
      std::printf("  simulation / Hertz: force %+.2f %%", 100.0 * d.force);
      if (d.contact_ended) std::printf(", duration %+.2f %%", 100.0 * d.duration);
      std::printf("\n");
    }
  }
}

// The stresses along the SIDs' lines at the force peak (result file: /stress_lines).
void printStressLinePeaks(const std::vector<StressLinePeak>& peaks) {
  for (const StressLinePeak& p : peaks) {
    if (p.von_mises < 0.0) continue;
    std::printf("  von Mises on %s/%s at the force peak: %.4g MPa at %.4g um", p.body.c_str(),
                p.line.c_str(), 1e-6 * p.von_mises, 1e6 * p.distance);
    if (p.hertz) {
      std::printf(" (Hertz %.4g MPa at %.4g um: %+.2f %%, %+.2f %%)", 1e-6 * p.hertz_von_mises,
                  1e6 * p.hertz_depth, 100.0 * (p.von_mises / p.hertz_von_mises - 1.0),
                  100.0 * (p.distance / p.hertz_depth - 1.0));
    }
    std::printf("\n");
  }
}

}  // namespace

HertzDifference differenceFrom(const HertzReference& h, const RunFigures& r) {
  HertzDifference d;
  d.force = r.max_contact_force / h.impact.max_force - 1.0;
  d.contact_ended = r.contact_begin >= 0.0 && r.contact_end >= 0.0;
  if (d.contact_ended) d.duration = (r.contact_end - r.contact_begin) / h.impact.duration - 1.0;
  return d;
}

void printSummary(const Scene& scene, const HertzReferences& hertz, const RunFigures& figures,
                  const std::vector<StressLinePeak>& peaks, long frames,
                  const std::string& xdmf_path) {
  std::printf("ffrsim %s: scene '%s': %s\n", kVersion, scene.name.c_str(), figures.status.c_str());
  printSolver(figures);
  printContact(scene, hertz, figures);
  printStressLinePeaks(peaks);
  if (frames > 0)
    std::printf("  %ld visualisation frames: open %s in ParaView\n", frames, xdmf_path.c_str());
}

}  // namespace ffriga
