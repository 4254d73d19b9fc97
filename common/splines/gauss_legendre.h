// Gauss-Legendre quadrature on [-1, 1] and on an interval [a, b]: n points integrate
// polynomials of degree <= 2n - 1 exactly. Nodes by Newton iteration on the three-term
// recurrence of the Legendre polynomials (Golub & Welsch give the same nodes), accurate
// to round-off for n <= 64.
#pragma once

#include <vector>

namespace ffriga {

struct QuadratureRule {
  std::vector<double> points;
  std::vector<double> weights;
};

// n >= 1 points on [-1, 1], nodes increasing.
QuadratureRule gaussLegendre(int n);
// The same rule mapped to [a, b] (weights scaled by (b - a) / 2).
QuadratureRule gaussLegendre(int n, double a, double b);

}  // namespace ffriga
