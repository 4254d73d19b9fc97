#include "runtime/bodies/rotational_coupling.h"

#include <catch2/catch.hpp>

#include "common/base/error.h"
#include "tests/support/synthetic_bodies.h"

using namespace ffriga;

// Z(:, c) = G_c x with G_c(j, i) = Cr1_j(c, i): the packed antisymmetric form against the
// sum over the SID's Cr1 as stored (sum_j x_j Cr1_j = -Z^T, rotational_coupling.h).
TEST_CASE("rotational coupling: packed antisymmetric products equal the Cr1 sums", "[ffr]") {
  const FlexibleBodySid sid = test::springBody(7, 2e3);
  const int nq = sid.nq();
  REQUIRE(nq >= 6);
  const RotationalCoupling G(sid, "b");
  Eigen::VectorXd x = Eigen::VectorXd::Random(nq);
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(3, nq);
  for (int j = 0; j < nq; ++j) sum += x(j) * sid.Cr1[j];
  Eigen::Matrix<double, Eigen::Dynamic, 3> Z, Zs;
  G.apply(x, Z);
  const double scale = sum.cwiseAbs().maxCoeff();
  REQUIRE(scale > 0.0);
  // Round-off of nq-term sums.
  CHECK((sum + Z.transpose()).cwiseAbs().maxCoeff() <= 1e-13 * nq * scale);
  // Sparse pass: the same products where x has zeros (the quasi-static rates).
  for (int i = 0; i < nq; i += 2) x(i) = 0.0;
  G.apply(x, Z);
  G.applySparse(x, Zs);
  CHECK((Z - Zs).cwiseAbs().maxCoeff() <= 1e-13 * nq * scale);
  // x^T G_c x = 0: the term (sum_j qdot_j Cr1_j) qdot of the quadratic velocity vector.
  for (int c = 0; c < 3; ++c) CHECK(std::abs(x.dot(Z.col(c))) <= 1e-13 * nq * scale * x.squaredNorm());
  // The upper triangle is Cr1 as stored, the lower one its negative transpose (the SID's
  // lower entries agree to round-off), the diagonal zero.
  double lower = 0.0;
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < nq; ++j) {
      CHECK(G.entry(c, j, j) == 0.0);
      for (int i = j + 1; i < nq; ++i) {
        CHECK(G.entry(c, j, i) == sid.Cr1[j](c, i));
        CHECK(G.entry(c, i, j) == -G.entry(c, j, i));
        lower = std::max(lower, std::abs(G.entry(c, i, j) - sid.Cr1[i](c, j)));
      }
    }
  CHECK(lower <= 1e-14 * scale);
}

TEST_CASE("rotational coupling: an SID whose Cr1 is not antisymmetric is refused", "[ffr]") {
  FlexibleBodySid sid = test::springBody(7, 2e3);
  sid.Cr1[1](2, 4) += 1e-6 * sid.Cr1[1].cwiseAbs().maxCoeff() + 1e-9;
  CHECK_THROWS_AS(RotationalCoupling(sid, "b"), InputError);
  try {
    RotationalCoupling(sid, "b");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("Cr1_1(2, 4)") != std::string::npos);
  }
}
