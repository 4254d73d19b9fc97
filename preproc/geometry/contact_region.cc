#include "preproc/geometry/contact_region.h"

#include <algorithm>
#include <limits>
#include <set>

#include "common/base/error.h"
#include "common/splines/gauss_legendre.h"

namespace ffriga {

namespace {
const char* kFaceNames[3][2] = {
    {"xi_min", "xi_max"}, {"eta_min", "eta_max"}, {"zeta_min", "zeta_max"}};
}

bool parseFaceName(const std::string& name, int* direction, bool* upper) {
  for (int a = 0; a < 3; ++a) {
    for (int u = 0; u < 2; ++u) {
      if (name == kFaceNames[a][u]) {
        *direction = a;
        *upper = u == 1;
        return true;
      }
    }
  }
  return false;
}

std::string faceName(int direction, bool upper) {
  return kFaceNames[direction][upper ? 1 : 0];
}

double faceCoordinate(const SplineSpace& space, const ContactRegion& r) {
  double lo = std::numeric_limits<double>::max(), hi = -lo;
  for (int e = 0; e < space.numElements(); ++e) {
    const ElementBox b = space.element(e);
    lo = std::min(lo, b.lower[r.direction]);
    hi = std::max(hi, b.upper[r.direction]);
  }
  return r.upper ? hi : lo;
}

std::vector<int> interfaceControlPoints(const SplineSpace& space, const ContactRegion& r) {
  const int d = space.paramDim();
  FFRIGA_CHECK(static_cast<int>(r.bounds.size()) == d - 1,
               "region has " << r.bounds.size() << " bounds, expected " << d - 1);
  const double face = faceCoordinate(space, r);
  const QuadratureRule g = gaussLegendre(4);
  std::set<int> found;
  PatchBasis basis;
  for (int e = 0; e < space.numElements(); ++e) {
    const ElementBox b = space.element(e);
    if ((r.upper ? b.upper : b.lower)[r.direction] != face) continue;
    // Overlap of the element's face with the region, per surface direction.
    std::array<double, 3> lo{}, hi{};
    bool empty = false;
    int s = 0;
    for (int a = 0; a < d; ++a) {
      if (a == r.direction) continue;
      lo[a] = std::max(b.lower[a], r.bounds[s][0]);
      hi[a] = std::min(b.upper[a], r.bounds[s][1]);
      empty = empty || !(hi[a] > lo[a]);
      ++s;
    }
    if (empty) continue;
    const int npts = d == 3 ? 16 : 4;
    for (int q = 0; q < npts; ++q) {
      double xi[3] = {0, 0, 0};
      int rest = q;
      for (int a = 0; a < d; ++a) {
        if (a == r.direction) {
          xi[a] = face;
          continue;
        }
        const double t = g.points[rest % 4];
        rest /= 4;
        xi[a] = lo[a] + 0.5 * (hi[a] - lo[a]) * (t + 1.0);
      }
      space.elementBasis(e, xi, 0, basis);
      const double top = basis.table.row(0).cwiseAbs().maxCoeff();
      for (std::size_t j = 0; j < basis.index.size(); ++j) {
        if (std::abs(basis.table(0, j)) > 1e-13 * top) found.insert(basis.index[j]);
      }
    }
  }
  return std::vector<int>(found.begin(), found.end());
}

}  // namespace ffriga
