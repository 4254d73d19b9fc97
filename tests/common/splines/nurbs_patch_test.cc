#include "common/splines/nurbs_patch.h"

#include <cmath>

#include <catch2/catch.hpp>

#include "tests/support/test_util.h"

using namespace ffriga;

TEST_CASE("rational basis: partition of unity, derivatives sum to zero", "[nurbs]") {
  for (int d = 1; d <= 3; ++d) {
    for (int trial = 0; trial < 10; ++trial) {
      const NurbsPatch patch = test::randomPatch(d, 3);
      PatchBasis R;
      for (int k = 0; k < 20; ++k) {
        double xi[3] = {test::uniform(), test::uniform(), test::uniform()};
        patch.basis(xi, 2, R);
        REQUIRE(R.table.rows() == numDerivativeRows(d, 2));
        REQUIRE(std::abs(R.table.row(0).sum() - 1.0) <= 1e-14);
        // Derivatives can be large on short spans; compare with the table's scale.
        const double scale = R.table.cwiseAbs().maxCoeff();
        for (int r = 1; r < R.table.rows(); ++r) {
          REQUIRE(std::abs(R.table.row(r).sum()) <= 1e-12 * scale);
        }
      }
    }
  }
}

TEST_CASE("patch derivatives agree with finite differences", "[nurbs]") {
  for (int d = 1; d <= 3; ++d) {
    for (int trial = 0; trial < 10; ++trial) {
      const NurbsPatch patch = test::randomPatch(d, 3);
      for (int k = 0; k < 10; ++k) {
        double xi[3] = {test::uniform(0.1, 0.9), test::uniform(0.1, 0.9), test::uniform(0.1, 0.9)};
        const PatchPoint pt = patch.evaluate(xi, 2);
        for (int a = 0; a < d; ++a) {
          const double h = 1e-7;
          // Skip stencils that cross a knot: derivatives jump there.
          bool crosses = false;
          for (double u : patch.knots(a).knots()) crosses |= (u > xi[a] - h && u < xi[a] + h);
          if (crosses) continue;
          double xp[3] = {xi[0], xi[1], xi[2]};
          double xm[3] = {xi[0], xi[1], xi[2]};
          xp[a] += h;
          xm[a] -= h;
          const PatchPoint p1 = patch.evaluate(xp, 1);
          const PatchPoint m1 = patch.evaluate(xm, 1);
          const Eigen::VectorXd fd = (p1.x - m1.x) / (2 * h);
          const double scale = 1.0 + pt.dx.cwiseAbs().maxCoeff() + pt.ddx.cwiseAbs().maxCoeff();
          REQUIRE((pt.dx.col(a) - fd).norm() <= 1e-5 * scale);
          for (int b = 0; b < d; ++b) {
            const Eigen::VectorXd fd2 = (p1.dx.col(b) - m1.dx.col(b)) / (2 * h);
            REQUIRE((pt.ddx.col(secondDerivativeRow(d, a, b) - 1 - d) - fd2).norm() <=
                    1e-5 * scale);
          }
        }
      }
    }
  }
}

TEST_CASE("a B-spline patch with unit weights is polynomial: linear precision", "[nurbs]") {
  // With control points at the Greville abscissae, x(xi) = xi exactly.
  for (int d = 1; d <= 3; ++d) {
    std::vector<KnotVector> U;
    for (int a = 0; a < d; ++a) U.push_back(test::randomKnots(test::uniformInt(1, 4), 3));
    int n = 1;
    for (const auto& u : U) n *= u.numBasis();
    Eigen::MatrixXd P(n, 3);
    P.setZero();
    NurbsPatch tmp(U, P, Eigen::VectorXd::Ones(n));
    for (int k = 0; k < n; ++k) {
      const auto i = tmp.tensorIndex(k);
      for (int a = 0; a < d; ++a) P(k, a) = U[a].greville()[i[a]];
    }
    const NurbsPatch patch(U, P, Eigen::VectorXd::Ones(n));
    for (int k = 0; k < 20; ++k) {
      double xi[3] = {test::uniform(), test::uniform(), test::uniform()};
      const PatchPoint pt = patch.evaluate(xi, 1);
      for (int a = 0; a < d; ++a) {
        REQUIRE(std::abs(pt.x(a) - xi[a]) <= 1e-14);
        REQUIRE(std::abs(pt.dx(a, a) - 1.0) <= 1e-12);
      }
    }
  }
}

TEST_CASE("patch construction checks sizes and weights", "[nurbs]") {
  const KnotVector U({0, 0, 1, 1}, 1);
  CHECK_THROWS_WITH(NurbsPatch({U}, Eigen::MatrixXd::Zero(3, 2), Eigen::VectorXd::Ones(3)),
                    Catch::Contains("2 basis functions but 3 control points"));
  CHECK_THROWS_WITH(NurbsPatch({U}, Eigen::MatrixXd::Zero(2, 2), Eigen::VectorXd::Ones(3)),
                    Catch::Contains("3 weights"));
  Eigen::VectorXd w(2);
  w << 1, -1;
  CHECK_THROWS_WITH(NurbsPatch({U}, Eigen::MatrixXd::Zero(2, 2), w), Catch::Contains("positive"));
}

TEST_CASE("coincident control points are grouped", "[nurbs]") {
  const KnotVector U({0, 0, 0, 1, 1, 1}, 2);
  Eigen::MatrixXd P(3, 2);
  P << 0, 0, 1, 0, 0, 1e-15;
  const NurbsPatch patch({U}, P, Eigen::VectorXd::Ones(3));
  const auto g = coincidentControlPoints(patch, 1e-12);
  REQUIRE(g.size() == 1u);
  CHECK(g[0] == std::vector<int>{0, 2});
}
