// The run against Hertz and the summary ffrsim prints at the end (the same figures are
// attributes of the result file: runtime/output/run_figures.h, run_attributes.h).
#pragma once

#include <string>
#include <vector>

#include "runtime/output/peak_stress_lines.h"
#include "runtime/output/run_figures.h"
#include "runtime/report/hertz_reference.h"
#include "runtime/scene/scene.h"

namespace ffriga {

// Relative differences of the force peak and, once the contact has ended, of its duration
// from Hertz's (simulation / Hertz - 1).
struct HertzDifference {
  double force = 0.0;
  bool contact_ended = false;
  double duration = 0.0;
};
HertzDifference differenceFrom(const HertzReference& hertz, const RunFigures& figures);

// The status, times, solver counts, phases, the contact figures with Hertz's, the stresses
// along lines at the force peak and the frames written, on stdout.
void printSummary(const Scene& scene, const HertzReferences& hertz, const RunFigures& figures,
                  const std::vector<StressLinePeak>& peaks, long frames,
                  const std::string& xdmf_path);

}  // namespace ffriga
