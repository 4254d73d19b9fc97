// The structured Newton matrix (runtime/integration/structured_newton.h): the Woodbury solve equals a
// dense solve of I - gamma (D + U V^T), and the multibody system's structured Jacobian equals
// its dense one where the neglected terms vanish.
#include <cmath>

#include <catch2/catch.hpp>

#include "runtime/bodies/floating_body.h"
#include "runtime/system/multibody_system.h"
#include "runtime/integration/structured_newton.h"
#include "tests/support/synthetic_bodies.h"
#include "tests/support/test_util.h"

using namespace ffriga;

TEST_CASE("structured Newton matrix: Woodbury solve equals the dense solve", "[ffr]") {
  for (int r : {0, 1, 7}) {
    StructuredJacobian J;
    J.n = 40;
    // 15 elastic pairs with stiff, damped modes (k up to 1e12 1/s^2) and a random low-rank
    // part of the size of contact terms.
    for (int i = 0; i < 15; ++i) {
      J.q_index.push_back(2 + i);
      J.v_index.push_back(20 + i);
    }
    J.k = (std::log(10.0) * Eigen::VectorXd::LinSpaced(15, 2.0, 12.0)).array().exp().matrix();
    J.c = 2.0 * J.k.cwiseSqrt();
    J.U = 1e3 * Eigen::MatrixXd::Random(J.n, r);
    J.V = 1e3 * Eigen::MatrixXd::Random(J.n, r);
    const double gamma = 1e-7;  // a BDF step of ~0.1 us
    StructuredNewtonMatrix N;
    REQUIRE(N.factor(gamma, J));
    const Eigen::MatrixXd dense = Eigen::MatrixXd::Identity(J.n, J.n) - gamma * J.dense();
    const Eigen::VectorXd b = Eigen::VectorXd::Random(J.n);
    Eigen::VectorXd x(J.n);
    N.solve(b.data(), x.data());
    const Eigen::VectorXd ref = dense.partialPivLu().solve(b);
    const double cond = dense.norm() * dense.inverse().norm();
    INFO("rank " << r << ", condition ~" << cond << ", error " << (x - ref).norm() / ref.norm()
                 << ", residual " << (dense * x - b).norm() / (dense.norm() * x.norm()));
    // The unit mix (positions, velocities) makes the matrix badly scaled (condition ~1e7 to
    // 1e10 in the 2-norm) but both solves are backward stable: normwise residuals at
    // round-off (1e-14 with margin), forward errors within eps * condition of each other.
    CHECK((dense * x - b).norm() <= 1e-14 * dense.norm() * x.norm());
    CHECK((x - ref).norm() <= 1e-14 * cond * ref.norm());
  }
}

TEST_CASE("structured Jacobian equals the dense Jacobian of a body at rest", "[ffr]") {
  // At rest (q = qdot = 0, v = w = 0) and without gravity, the terms the structured form
  // neglects (the q-dependence of M(q) times accelerations, velocity-quadratic forces)
  // vanish: both Jacobians describe the same linearisation.
  auto sid = std::make_shared<FlexibleBodySid>(test::springBody(5, 2e3));
  sid->De = 0.01 * sid->Ke;  // diagonal modal damping
  MultibodySystem sys;
  sys.addBody(std::make_unique<FloatingBody3d>("b", sid));
  REQUIRE(sys.body(0).diagonalElasticity());
  const int n = sys.size();
  Eigen::VectorXd y = Eigen::VectorXd::Zero(n);
  y.segment<4>(3) = Eigen::Vector4d(0.9, 0.1, -0.3, 0.2).normalized();
  Eigen::VectorXd f(n);
  sys.rhs(0.0, y.data(), f.data());
  const Eigen::VectorXd scale = Eigen::VectorXd::Ones(n);
  Eigen::MatrixXd Jd = Eigen::MatrixXd::Zero(n, n);
  REQUIRE(sys.jacobian(0.0, y.data(), f.data(), scale.data(), Jd.data()));
  StructuredJacobian Js;
  REQUIRE(sys.structuredJacobian(0.0, y.data(), scale.data(), Js));
  // Both take one-sided quotients (step ~1.5e-8) in the rigid columns, and the dense one
  // in the elastic columns too (error ~1e-8 |f''|): 1e-6 of the largest entry.
  CHECK((Js.dense() - Jd).cwiseAbs().maxCoeff() <= 1e-6 * Jd.cwiseAbs().maxCoeff());
}
