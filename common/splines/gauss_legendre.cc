#include "common/splines/gauss_legendre.h"

#include <cmath>

#include "common/base/error.h"

namespace ffriga {

QuadratureRule gaussLegendre(int n) {
  FFRIGA_CHECK(n >= 1 && n <= 64, "n = " << n);
  QuadratureRule rule;
  rule.points.resize(n);
  rule.weights.resize(n);
  const double pi = std::acos(-1.0);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    // Initial guess (Tricomi), then Newton on P_n.
    double x = std::cos(pi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0;
      double p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    // Recompute the derivative at the converged node for the weight.
    double p0 = 1.0;
    double p1 = x;
    for (int k = 2; k <= n; ++k) {
      const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
      p0 = p1;
      p1 = p2;
    }
    dp = n * (x * p1 - p0) / (x * x - 1.0);
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    rule.points[i] = -x;
    rule.points[n - 1 - i] = x;
    rule.weights[i] = w;
    rule.weights[n - 1 - i] = w;
  }
  if (n % 2 == 1) rule.points[n / 2] = 0.0;
  return rule;
}

QuadratureRule gaussLegendre(int n, double a, double b) {
  QuadratureRule rule = gaussLegendre(n);
  const double h = 0.5 * (b - a);
  const double c = 0.5 * (a + b);
  for (int i = 0; i < n; ++i) {
    rule.points[i] = c + h * rule.points[i];
    rule.weights[i] *= h;
  }
  return rule;
}

}  // namespace ffriga
