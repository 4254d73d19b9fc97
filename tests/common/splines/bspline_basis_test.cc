#include "common/splines/bspline_basis.h"

#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "tests/support/test_util.h"

using namespace ffriga;

namespace {

// Paper Eq. (2)-(3), Cox-de Boor recursion, as an independent reference (0/0 := 0).
double coxDeBoor(const std::vector<double>& U, int i, int p, double u) {
  if (p == 0) {
    if (U[i] <= u && u < U[i + 1]) return 1.0;
    // Right end of the domain belongs to the last non-empty span.
    if (u == U.back() && U[i] < U[i + 1] && U[i + 1] == U.back()) return 1.0;
    return 0.0;
  }
  double v = 0.0;
  if (U[i + p] > U[i]) v += (u - U[i]) / (U[i + p] - U[i]) * coxDeBoor(U, i, p - 1, u);
  if (U[i + p + 1] > U[i + 1]) {
    v += (U[i + p + 1] - u) / (U[i + p + 1] - U[i + 1]) * coxDeBoor(U, i + 1, p - 1, u);
  }
  return v;
}

}  // namespace

TEST_CASE("A2.2 equals the Cox-de Boor recursion and sums to one", "[bspline]") {
  for (int trial = 0; trial < 60; ++trial) {
    const int p = test::uniformInt(1, 6);
    const KnotVector U = test::randomKnots(p, test::uniformInt(0, 6));
    double N[kMaxDegree + 1];
    for (int k = 0; k < 50; ++k) {
      const double u = k == 0 ? 1.0 : test::uniform();
      const int s = U.findSpan(u);
      basisFunctions(U, s, u, N);
      double sum = 0.0;
      for (int j = 0; j <= p; ++j) {
        // Partition of unity and non-negativity: exact up to a few ulp per recursion level.
        REQUIRE(N[j] >= -1e-15);
        REQUIRE(std::abs(N[j] - coxDeBoor(U.knots(), s - p + j, p, u)) <= 1e-14);
        sum += N[j];
      }
      REQUIRE(std::abs(sum - 1.0) <= 1e-14);
    }
  }
}

TEST_CASE("A2.3 derivatives agree with A2.2 and with finite differences", "[bspline]") {
  for (int trial = 0; trial < 60; ++trial) {
    const int p = test::uniformInt(1, 6);
    const KnotVector U = test::randomKnots(p, test::uniformInt(0, 5));
    const int P = p + 1;
    double D[(kMaxDegree + 1) * (kMaxDegree + 1)];
    double N[kMaxDegree + 1];
    double Dp[(kMaxDegree + 1) * 3];
    double Dm[(kMaxDegree + 1) * 3];
    for (int k = 0; k < 30; ++k) {
      const double u = test::uniform(0.01, 0.99);
      const int s = U.findSpan(u);
      // Keep the difference stencil inside the span: the basis is only piecewise smooth.
      const double h = 1e-6 * (U[s + 1] - U[s]);
      if (u - h < U[s] || u + h >= U[s + 1]) continue;
      basisFunctionDerivatives(U, s, u, p, D);
      basisFunctions(U, s, u, N);
      basisFunctionDerivatives(U, s, u + h, 2, Dp);
      basisFunctionDerivatives(U, s, u - h, 2, Dm);
      double sum1 = 0.0;
      for (int j = 0; j <= p; ++j) {
        REQUIRE(D[j] == Approx(N[j]).margin(1e-15));
        // Central differences: error O(h^2 f''') + O(eps f / h). Scale by the span length.
        const double L = U[s + 1] - U[s];
        const double fd1 = (Dp[j] - Dm[j]) / (2 * h);
        REQUIRE(std::abs(D[P + j] - fd1) <= 1e-6 * (1.0 / L));
        if (p >= 2) {
          const double fd2 = (Dp[P + j] - Dm[P + j]) / (2 * h);
          REQUIRE(std::abs(D[2 * P + j] - fd2) <= 1e-6 / (L * L));
        }
        sum1 += D[P + j];
      }
      // Derivatives of a partition of unity sum to zero.
      REQUIRE(std::abs(sum1) <= 1e-10 / (U[s + 1] - U[s]));
    }
  }
}

TEST_CASE("derivatives above the degree vanish and degree-p derivative is constant", "[bspline]") {
  const KnotVector U({0, 0, 0, 0.3, 0.7, 1, 1, 1}, 2);
  double D[4 * 3];
  basisFunctionDerivatives(U, 3, 0.5, 3, D);
  for (int j = 0; j < 3; ++j) CHECK(D[9 + j] == 0.0);
  double E[4 * 3];
  basisFunctionDerivatives(U, 3, 0.6, 2, E);
  for (int j = 0; j < 3; ++j) CHECK(E[6 + j] == Approx(D[6 + j]).epsilon(1e-12));
}
