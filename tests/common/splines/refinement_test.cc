#include "common/splines/refinement.h"

#include <cmath>

#include <catch2/catch.hpp>

#include "common/splines/bspline_basis.h"
#include "tests/support/test_util.h"

using namespace ffriga;

namespace {

NurbsPatch randomPatch(int d) {
  std::vector<KnotVector> U;
  int n = 1;
  for (int a = 0; a < d; ++a) {
    U.push_back(test::randomKnots(test::uniformInt(1, 3), test::uniformInt(0, 3)));
    n *= U.back().numBasis();
  }
  Eigen::MatrixXd P = Eigen::MatrixXd::Random(n, 3);
  Eigen::VectorXd w(n);
  for (int k = 0; k < n; ++k) w(k) = test::uniform(0.5, 2.0);
  return NurbsPatch(U, P, w);
}

// Largest distance between two patches over random points, relative to the patch size.
double maxRelativeDifference(const NurbsPatch& a, const NurbsPatch& b, int samples) {
  const double size = (a.points().colwise().maxCoeff() - a.points().colwise().minCoeff()).norm();
  double err = 0.0;
  for (int k = 0; k < samples; ++k) {
    double xi[3] = {test::uniform(), test::uniform(), test::uniform()};
    if (k == 0) xi[0] = xi[1] = xi[2] = 1.0;  // the right end of the domain
    err = std::max(err, (a.evaluate(xi).x - b.evaluate(xi).x).norm() / size);
  }
  return err;
}

// Values of all basis functions of U at u (dense vector).
Eigen::VectorXd allBasis(const KnotVector& U, double u) {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(U.numBasis());
  double N[kMaxDegree + 1];
  const int s = U.findSpan(u);
  basisFunctions(U, s, u, N);
  for (int j = 0; j <= U.degree(); ++j) v(s - U.degree() + j) = N[j];
  return v;
}

}  // namespace

TEST_CASE("knot insertion and degree elevation leave patches unchanged", "[refinement]") {
  // 1e-13 relative (issue #2): each step adds a few ulp per control point.
  for (int d = 1; d <= 3; ++d) {
    for (int trial = 0; trial < 8; ++trial) {
      const NurbsPatch patch = randomPatch(d);
      for (int dir = 0; dir < d; ++dir) {
        std::vector<double> X;
        for (int k = 0; k < 5; ++k) X.push_back(test::uniform(0.01, 0.99));
        if (patch.degree(dir) >= 2) X.push_back(X[0]);  // a repeated knot
        const NurbsPatch refined = insertKnots(patch, dir, X);
        CHECK(refined.numBasis(dir) == patch.numBasis(dir) + static_cast<int>(X.size()));
        REQUIRE(maxRelativeDifference(patch, refined, 200) <= 1e-13);
        const int t = test::uniformInt(1, 3);
        const NurbsPatch elevated = elevateDegree(patch, dir, t);
        CHECK(elevated.degree(dir) == patch.degree(dir) + t);
        REQUIRE(maxRelativeDifference(patch, elevated, 200) <= 1e-13);
        // Elevation after insertion, insertion after elevation: same geometry.
        const NurbsPatch both = insertKnots(elevateDegree(refined, dir, 1), dir, {0.5});
        REQUIRE(maxRelativeDifference(patch, both, 200) <= 1e-13);
      }
    }
  }
}

TEST_CASE("transfer matrix expresses coarse functions by fine ones", "[refinement]") {
  // N_i(u) = sum_j T(j, i) Nbar_j(u) for general non-uniform knots.
  for (int trial = 0; trial < 20; ++trial) {
    const KnotVector U = test::randomKnots(test::uniformInt(1, 5), test::uniformInt(0, 4));
    std::vector<double> X;
    for (int k = 0; k < 7; ++k) X.push_back(test::uniform(0.01, 0.99));
    KnotVector F;
    const Eigen::MatrixXd T = knotInsertionMatrix(U, X, &F);
    const Eigen::SparseMatrix<double> S = refinementMatrix(U, F);
    REQUIRE((Eigen::MatrixXd(S) - T).norm() == 0.0);
    // Columns sum to... rows sum to one (partition of unity is preserved).
    REQUIRE((T.rowwise().sum().array() - 1.0).abs().maxCoeff() <= 1e-14);
    for (int k = 0; k < 50; ++k) {
      const double u = test::uniform();
      REQUIRE((allBasis(U, u) - T.transpose() * allBasis(F, u)).cwiseAbs().maxCoeff() <= 1e-14);
    }
    // Degree elevation: same identity with the elevated basis.
    KnotVector E;
    const Eigen::MatrixXd Te = degreeElevationMatrix(U, 2, &E);
    for (int k = 0; k < 50; ++k) {
      const double u = test::uniform();
      REQUIRE((allBasis(U, u) - Te.transpose() * allBasis(E, u)).cwiseAbs().maxCoeff() <= 1e-13);
    }
  }
}

TEST_CASE("uniform halving reproduces the two-scale coefficients of Eq. (8)", "[refinement]") {
  // a_j = 2^-p binom(p+1, j) for an interior B-spline of a uniform knot vector.
  for (int p = 1; p <= 5; ++p) {
    const KnotVector U = KnotVector::uniform(p, 3 * p + 2);
    KnotVector F;
    const Eigen::MatrixXd T = knotInsertionMatrix(U, uniformInsertionKnots(U, 1), &F);
    const int i = (U.numBasis() - 1) / 2;  // an interior function, support away from the ends
    REQUIRE(U[i] > 0.0);
    REQUIRE(U[i + p + 1] < 1.0);
    const int first = 2 * i - p;  // finest function starting at knot u_i
    double binom = 1.0;
    for (int j = 0; j <= p + 1; ++j) {
      REQUIRE(T(first + j, i) == Approx(std::ldexp(binom, -p)).epsilon(1e-14));
      binom = binom * (p + 1 - j) / (j + 1);
    }
    REQUIRE(T.col(i).cwiseAbs().sum() == Approx(2.0).epsilon(1e-14));
  }
}

TEST_CASE("refinement rejects knots it cannot insert", "[refinement]") {
  const KnotVector U({0, 0, 0, 0.5, 1, 1, 1}, 2);
  KnotVector F;
  CHECK_THROWS_WITH(knotInsertionMatrix(U, {1.5}, &F), Catch::Contains("outside"));
  CHECK_THROWS_WITH(knotInsertionMatrix(U, {0.5, 0.5}, &F), Catch::Contains("multiplicity 3"));
  CHECK_THROWS_WITH(knotInsertionMatrix(U, {0.0}, &F), Catch::Contains("end of the domain"));
  CHECK_THROWS(refinementMatrix(U, KnotVector({0, 0, 0, 1, 1, 1}, 2)));
}
