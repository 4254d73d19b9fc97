#include "common/splines/bspline_basis.h"

#include <utility>

#include "common/base/error.h"

namespace ffriga {

void basisFunctions(const KnotVector& knots, int span, double u, double* N) {
  const int p = knots.degree();
  const double* U = knots.data();
  double left[kMaxDegree + 1];
  double right[kMaxDegree + 1];
  N[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - U[span + 1 - j];
    right[j] = U[span + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = N[r] / (right[r + 1] + left[j - r]);
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
}

void basisFunctionDerivatives(const KnotVector& knots, int span, double u, int nders,
                              double* ders) {
  const int p = knots.degree();
  const double* U = knots.data();
  FFRIGA_ASSERT(nders >= 0 && nders <= kMaxDegree, "nders = " << nders);
  constexpr int W = kMaxDegree + 1;
  double ndu[W][W];  // ndu[j][r]: basis values (upper triangle) and knot differences (lower)
  double a[2][W];
  double left[W];
  double right[W];

  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - U[span + 1 - j];
    right[j] = U[span + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  const int P = p + 1;
  for (int j = 0; j <= p; ++j) ders[j] = ndu[j][p];
  for (int k = p + 1; k <= nders; ++k) {
    for (int j = 0; j <= p; ++j) ders[k * P + j] = 0.0;
  }
  const int kmax = nders < p ? nders : p;
  for (int r = 0; r <= p; ++r) {
    int s1 = 0;
    int s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= kmax; ++k) {
      double d = 0.0;
      const int rk = r - k;
      const int pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      ders[k * P + r] = d;
      std::swap(s1, s2);
    }
  }
  double factor = p;
  for (int k = 1; k <= kmax; ++k) {
    for (int j = 0; j <= p; ++j) ders[k * P + j] *= factor;
    factor *= (p - k);
  }
}

}  // namespace ffriga
