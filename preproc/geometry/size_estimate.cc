#include "preproc/geometry/size_estimate.h"

#include <unistd.h>

#include <cmath>

#include "common/base/error.h"

namespace ffriga {

namespace {

// Matrix sizes from the number of functions per direction and the degrees.
SizeEstimate fromFunctions(const std::vector<double>& n, const std::vector<double>& degree, int s) {
  SizeEstimate e;
  e.control_points = 1.0;
  double coupling = 1.0;  // functions whose supports overlap one function's, per direction
  for (std::size_t a = 0; a < n.size(); ++a) {
    e.control_points *= n[a];
    coupling *= 2.0 * degree[a] + 1.0;
  }
  e.dofs = e.control_points * s;
  e.nonzeros = 0.5 * e.dofs * coupling * s;
  const double fill = n.size() == 3 ? 20.0 : 5.0;
  e.bytes = 12.0 * e.nonzeros * (2.0 + fill);
  return e;
}

}  // namespace

SizeEstimate estimateSize(const NurbsPatch& patch, const RefinementConfig& config) {
  const int d = patch.paramDim();
  std::vector<double> n(d), degree(d);
  for (int a = 0; a < d; ++a) {
    const KnotVector& U = patch.knots(a);
    const double spans = U.numElements();
    const int elevate = a < static_cast<int>(config.elevate_degree.size()) ? config.elevate_degree[a] : 0;
    const int perSpan = a < static_cast<int>(config.insert_knots.size()) ? config.insert_knots[a] : 0;
    degree[a] = U.degree() + std::max(elevate, 0);
    // Elevation raises every break's multiplicity: one more function per span and order;
    // uniform insertion adds perSpan per span; explicit knots one each.
    n[a] = U.numBasis() + std::max(elevate, 0) * spans + std::max(perSpan, 0) * spans;
    if (a < static_cast<int>(config.insert.size())) n[a] += config.insert[a].size();
  }
  return fromFunctions(n, degree, patch.spaceDim());
}

SizeEstimate estimateGlobalReferenceSize(const NurbsPatch& refined,
                                         const HierarchyOptions& hierarchy) {
  const int d = refined.paramDim();
  std::vector<double> n(d), degree(d);
  for (int a = 0; a < d; ++a) {
    const KnotVector& U = refined.knots(a);
    degree[a] = U.degree();
    n[a] = U.numBasis();
    // Level l halves the level l - 1 spans inside its boxes: as many new knot lines as the
    // boxes hold level-0 spans along a (each span once) times 2^(l - 1), inserted across
    // the whole patch.
    const std::vector<double> breaks = U.breaks();
    for (int l = 1; l < hierarchy.levels; ++l) {
      double inside = 0.0;
      for (std::size_t k = 0; k + 1 < breaks.size(); ++k)
        if (intervalInBoxes(hierarchy.boxes[l - 1], a, breaks[k], breaks[k + 1])) inside += 1.0;
      n[a] += inside * std::pow(2.0, l - 1);
    }
  }
  return fromFunctions(n, degree, refined.spaceDim());
}

double physicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? static_cast<double>(pages) * static_cast<double>(size) : 0.0;
}

}  // namespace ffriga
