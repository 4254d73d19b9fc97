#include "preproc/geometry/patch_volume.h"

#include <array>
#include <cmath>

#include "common/splines/gauss_legendre.h"

namespace ffriga {

namespace {
// Each element is integrated in 8 pieces per direction: a rational patch is no polynomial.
constexpr int kPiecesPerElement = 8;
}  // namespace

double patchVolume(const NurbsPatch& patch, bool axisymmetric) {
  const int d = patch.paramDim();
  // Per direction: the quadrature points of all its elements, with weights.
  std::array<QuadratureRule, 3> lines;
  for (int a = 0; a < d; ++a) {
    const std::vector<double> breaks = patch.knots(a).breaks();
    for (std::size_t e = 0; e + 1 < breaks.size(); ++e) {
      for (int k = 0; k < kPiecesPerElement; ++k) {
        const double h = (breaks[e + 1] - breaks[e]) / kPiecesPerElement;
        const double lo = breaks[e] + k * h;
        const QuadratureRule g = gaussLegendre(patch.degree(a) + 2, lo, lo + h);
        lines[a].points.insert(lines[a].points.end(), g.points.begin(), g.points.end());
        lines[a].weights.insert(lines[a].weights.end(), g.weights.begin(), g.weights.end());
      }
    }
  }
  const std::size_t n1 = d > 1 ? lines[1].points.size() : 1;
  const std::size_t n2 = d > 2 ? lines[2].points.size() : 1;
  double volume = 0.0;
  for (std::size_t k = 0; k < n2; ++k) {
    for (std::size_t j = 0; j < n1; ++j) {
      for (std::size_t i = 0; i < lines[0].points.size(); ++i) {
        const std::array<std::size_t, 3> q{i, j, k};
        double xi[3] = {0.0, 0.0, 0.0}, w = 1.0;
        for (int a = 0; a < d; ++a) {
          xi[a] = lines[a].points[q[a]];
          w *= lines[a].weights[q[a]];
        }
        const PatchPoint p = patch.evaluate(xi, 1);
        double dv = std::abs(p.dx.determinant()) * w;
        if (axisymmetric) dv *= 2.0 * M_PI * p.x(0);
        volume += dv;
      }
    }
  }
  return volume;
}

}  // namespace ffriga
