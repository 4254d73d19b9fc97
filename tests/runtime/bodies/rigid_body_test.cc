// Rigid and frozen bodies' SIDs (runtime/bodies/rigid_body.h), directly: the inertia about
// the frame origin by the parallel axis theorem against point-mass sums, the physical-body
// checks on the inertia tensor, and a frozen SID that keeps exactly the rigid invariants.
#include "runtime/bodies/rigid_body.h"

#include <limits>

#include <catch2/catch.hpp>

#include "common/base/error.h"
#include "runtime/bodies/floating_body.h"
#include "tests/support/synthetic_bodies.h"

using namespace ffriga;

TEST_CASE("rigid body SID: invariants of a point-mass body about its frame origin", "[rigid]") {
  // Five point masses: their mass, centre c and inertia I_c about c are the scene's input;
  // the SID's m c and J0 must equal the sums m_a x_a and m_a (x_a.x_a E - x_a x_a^T) about
  // the frame origin (round-off of sums of ~1e-2 kg m^2).
  Eigen::MatrixXd X(5, 3);
  X << 0.1, 0.0, 0.2, -0.3, 0.1, 0.0, 0.05, -0.2, 0.1, 0.2, 0.2, -0.1, 0.0, 0.0, 0.3;
  const Eigen::VectorXd m = (Eigen::VectorXd(5) << 1.0, 2.0, 0.5, 1.5, 0.7).finished();
  RigidBodyProperties p;
  p.mass = m.sum();
  for (int a = 0; a < 5; ++a) p.centre_of_mass += m(a) * X.row(a).transpose() / p.mass;
  Eigen::Matrix3d J0 = Eigen::Matrix3d::Zero();
  for (int a = 0; a < 5; ++a) {
    const Eigen::Vector3d x = X.row(a).transpose(), xc = x - p.centre_of_mass;
    p.inertia += m(a) * (xc.squaredNorm() * Eigen::Matrix3d::Identity() - xc * xc.transpose());
    J0 += m(a) * (x.squaredNorm() * Eigen::Matrix3d::Identity() - x * x.transpose());
  }
  const FlexibleBodySid s = rigidBodySid("points", p);
  CHECK(s.name == "points");
  CHECK(s.mass == p.mass);
  CHECK(s.nq() == 0);
  CHECK((s.first_moment - X.transpose() * m).cwiseAbs().maxCoeff() < 1e-15);
  CHECK((s.inertia - J0).cwiseAbs().maxCoeff() < 1e-15);
  // The body model takes it: kinetic energy of a pure rotation w about the origin is
  // 1/2 w^T J0 w (exactly the same sums).
  const FloatingBody3d body("points", std::make_shared<FlexibleBodySid>(s));
  Eigen::VectorXd sp(7), sv(6);
  sp << 0, 0, 0, 1, 0, 0, 0;
  sv << 0, 0, 0, 1.0, -2.0, 0.5;
  const Eigen::Vector3d w = sv.tail<3>();
  CHECK(body.kineticEnergy(sp.data(), sv.data()) == Approx(0.5 * w.dot(J0 * w)).epsilon(1e-14));
}

TEST_CASE("rigid body SID: masses and inertia tensors no body can have are refused", "[rigid]") {
  RigidBodyProperties good;
  good.mass = 1.0;
  good.inertia = Eigen::Vector3d(1.0, 1.5, 2.0).asDiagonal();
  CHECK_NOTHROW(rigidBodySid("good", good));
  auto refused = [&](RigidBodyProperties p, const std::string& words) {
    try {
      rigidBodySid("bad", p);
    } catch (const InputError& e) {
      INFO(e.what());
      CHECK(std::string(e.what()).find(words) != std::string::npos);
      return true;
    }
    return false;
  };
  RigidBodyProperties p = good;
  p.mass = 0.0;
  CHECK(refused(p, "mass > 0"));
  p.mass = std::numeric_limits<double>::infinity();
  CHECK(refused(p, "mass > 0"));
  p = good;
  p.inertia(0, 1) = 0.1;  // not symmetric
  CHECK(refused(p, "symmetric"));
  p = good;
  p.inertia(2, 2) = -0.5;
  CHECK(refused(p, "positive definite"));
  p = good;
  p.inertia(2, 2) = 2.6;  // 2.6 > 1.0 + 1.5
  CHECK(refused(p, "triangle inequality"));
  p.inertia(2, 2) = 2.5;  // the limit (a flat plate) is a real body
  CHECK_FALSE(refused(p, ""));
}

TEST_CASE("frozen SID: the flexible body's rigid invariants, no elastic coordinates", "[rigid]") {
  const FlexibleBodySid flex = test::springBody(4, 2e3);
  const FlexibleBodySid f = frozenSid(flex);
  CHECK(f.nq() == 0);
  CHECK(f.mass == flex.mass);
  CHECK(f.first_moment == flex.first_moment);
  CHECK(f.inertia == flex.inertia);
  CHECK(f.control_points == flex.control_points);
  CHECK(f.Phi.rows() == flex.Phi.rows());
  CHECK(f.Phi.cols() == 0);
  // As a body model: the same mass matrix as the flexible body's rigid block at q = 0.
  const FloatingBody3d frozen("f", std::make_shared<FlexibleBodySid>(f));
  const FloatingBody3d flexible("b", std::make_shared<FlexibleBodySid>(flex));
  CHECK(frozen.massMatrix(Eigen::VectorXd()) ==
        flexible.massMatrix(Eigen::VectorXd::Zero(4)).topLeftCorner(6, 6));
}
