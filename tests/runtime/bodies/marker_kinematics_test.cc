// Rotations (runtime/bodies/rotation.h), markers (runtime/bodies/body_marker.h) and their
// kinematics (runtime/bodies/marker_kinematics.h), directly: the rotation matrix of a
// quaternion against Eigen's, the quaternion rate against dA/dt = A w~, a SID marker's modes,
// and the marker's value, rate G z and bias against difference quotients along exact motions
// (tests/support/body_motion.h), with G^T f the generalised force of a point force.
#include "runtime/bodies/marker_kinematics.h"

#include <cmath>
#include <memory>
#include <random>

#include <catch2/catch.hpp>

#include "runtime/bodies/body_marker.h"
#include "runtime/bodies/rotation.h"
#include "tests/support/body_motion.h"
#include "tests/support/synthetic_bodies.h"

using namespace ffriga;

TEST_CASE("rotation: the quaternion's matrix, its scale invariance, and the quaternion rate",
          "[rotation]") {
  std::mt19937 gen(41);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector4d p = test::randomQuaternion(gen);
    const Eigen::Matrix3d A = rotationMatrix(p.data());
    // Orthonormal with det +1, and Eigen's matrix of the same quaternion (scalar first):
    // round-off of sums of a few products of unit numbers, a few eps (seen up to 4 eps).
    const double tol = 4e-15;
    CHECK((A.transpose() * A - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < tol);
    CHECK(std::abs(A.determinant() - 1.0) < tol);
    const Eigen::Quaterniond e(p(0), p(1), p(2), p(3));
    CHECK((A - e.toRotationMatrix()).cwiseAbs().maxCoeff() < tol);
    // A drifted |p| is normalised away.
    const Eigen::Vector4d p3 = 3.0 * p;
    CHECK((rotationMatrix(p3.data()) - A).cwiseAbs().maxCoeff() < tol);
    // skew(a) b = a x b: the same products, summed with zeros in another order (an ulp or
    // two of numbers of size 1).
    const Eigen::Vector3d a = test::randomMatrix(gen, 3, 1), b = test::randomMatrix(gen, 3, 1);
    CHECK((skew(a) * b - a.cross(b)).cwiseAbs().maxCoeff() < 1e-15);
    // The quaternion rate keeps |p| (p . pdot = 0) and gives dA/dt = A w~ for the body
    // angular velocity w: fourth-order differences along p + t pdot with step 1e-3
    // (truncation h^4 |w|^5 / 30 < 1e-10 for |w| < 5.2, round-off ~eps / h ~ 2e-13).
    const Eigen::Vector3d w = test::randomMatrix(gen, 3, 1, 3.0);
    Eigen::Vector4d pdot;
    quaternionRate(p.data(), w, pdot.data());
    CHECK(std::abs(p.dot(pdot)) < 1e-15);
    auto along = [&](double t) {
      const Eigen::Vector4d pt = p + t * pdot;
      const Eigen::Matrix3d At = rotationMatrix(pt.data());
      return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(At.data(), 9));
    };
    const Eigen::VectorXd Adot = test::firstDerivative(along, 1e-3);
    const Eigen::Matrix3d AW = A * skew(w);
    CHECK((Adot - Eigen::Map<const Eigen::VectorXd>(AW.data(), 9)).cwiseAbs().maxCoeff() < 1e-9);
  }
}

TEST_CASE("body markers: a SID marker's modes, a fixed marker and the ground", "[markers]") {
  // Marker of the spring body at the point with basis values 0.25, 0.75 on control points 3
  // and 8: Phi = 0.25 Phi_3 + 0.75 Phi_8 (rows of the SID's modes), Psi as given.
  const FlexibleBodySid sid = test::springBody(4, 2e3);
  Marker m;
  m.name = "mid";
  m.position =
      0.25 * sid.control_points.row(3).transpose() + 0.75 * sid.control_points.row(8).transpose();
  m.functions = {3, 8};
  m.values = Eigen::Vector2d(0.25, 0.75);
  m.Psi = Eigen::MatrixXd::Constant(3, 4, 0.5);
  const BodyMarker b = markerFromSid(sid, m, 4);
  CHECK(b.name == "mid");
  CHECK(b.x0 == m.position);
  CHECK((b.Phi - (0.25 * sid.Phi.middleRows(9, 3) + 0.75 * sid.Phi.middleRows(24, 3)))
            .cwiseAbs()
            .maxCoeff() < 1e-16);
  CHECK(b.rotation_modes);
  CHECK(b.Psi == m.Psi);
  // Without rotation modes in the SID: flagged, Psi zero (nothing may use it).
  m.Psi.resize(0, 0);
  const BodyMarker noPsi = markerFromSid(sid, m, 4);
  CHECK_FALSE(noPsi.rotation_modes);
  CHECK(noPsi.Psi.isZero(0.0));
  CHECK(noPsi.Psi.cols() == 4);
  // A frozen body (nq = 0): no modes, rotation usable.
  const BodyMarker frozen = markerFromSid(sid, m, 0);
  CHECK(frozen.Phi.cols() == 0);
  CHECK(frozen.rotation_modes);
  const BodyMarker fixed = fixedMarker("f", {1.0, 2.0, 3.0});
  CHECK(fixed.Phi.rows() == 3);
  CHECK(fixed.Phi.cols() == 0);
  // The ground: a fixed value, no velocity columns.
  MarkerKinematics k;
  groundKinematics({1.0, 2.0, 3.0}, k);
  CHECK(k.value == Eigen::Vector3d(1, 2, 3));
  CHECK(k.G.cols() == 0);
  CHECK(k.rate.isZero(0.0));
  CHECK(k.bias.isZero(0.0));
}

TEST_CASE("marker kinematics: value, G z and bias are the derivatives along exact motions",
          "[markers]") {
  // Rigid and flexible bodies, markers with random Phi (~0.05 m) and Psi (~0.5 rad) per unit
  // q, at random states: the point R and an attached vector U against their position-level
  // formulas, their first and second time derivatives under constant z (dz/dt = 0, so
  // d2/dt2 is the bias alone), and G^T f as the generalised force of f (virtual power
  // f . G z = (G^T f) . z).
  std::mt19937 gen(42);
  for (const bool flexible : {false, true}) {
    auto sid = std::make_shared<FlexibleBodySid>(flexible ? test::springBody(4, 2e3)
                                                          : test::rigidBody(1.0, {1.0, 2.0, 2.0}));
    const FloatingBody3d body("b", sid);
    const int nq = body.nq();
    BodyMarker m = fixedMarker("m", {0.05, -0.1, 0.08});
    if (flexible) {
      m.Phi = test::randomMatrix(gen, 3, nq, 0.05);
      m.Psi = test::randomMatrix(gen, 3, nq, 0.5);
    }
    Eigen::VectorXd sp(7 + nq), sv(6 + nq);
    sp << test::randomMatrix(gen, 3, 1, 0.3), test::randomQuaternion(gen),
        test::randomMatrix(gen, nq, 1, 1e-2);
    sv << test::randomMatrix(gen, 3, 1, 0.5), test::randomMatrix(gen, 3, 1, 2.0),
        test::randomMatrix(gen, nq, 1, 1.0);
    const Eigen::Vector3d u0 = Eigen::Vector3d(0.3, -0.4, 1.0).normalized();
    MarkerKinematics kp, kv;
    markerPoint(body, sp.data(), sv.data(), m, kp);
    markerVector(body, sp.data(), sv.data(), m, u0, kv);
    const Eigen::Matrix3d A = rotationMatrix(sp.data() + 3);
    const Eigen::VectorXd q = sp.tail(nq);
    // Position level, written out (header): R = r + A (x0 + Phi q), U = A (u0 + (Psi q) x u0).
    const Eigen::Vector3d R = sp.head<3>() + A * (m.x0 + m.Phi * q);
    const Eigen::Vector3d theta = m.Psi * q;
    const Eigen::Vector3d U = A * (u0 + theta.cross(u0));
    CHECK((kp.value - R).cwiseAbs().maxCoeff() < 1e-15);
    CHECK((kv.value - U).cwiseAbs().maxCoeff() < 1e-15);
    CHECK((kp.G * sv - kp.rate).cwiseAbs().maxCoeff() < 1e-14);
    CHECK((kv.G * sv - kv.rate).cwiseAbs().maxCoeff() < 1e-14);
    auto along = [&](double t) {
      const Eigen::VectorXd s = test::flowPositions(sp, sv, t);
      MarkerKinematics a, b;
      markerPoint(body, s.data(), sv.data(), m, a);
      markerVector(body, s.data(), sv.data(), m, u0, b);
      Eigen::VectorXd out(6);
      out << a.value, b.value;
      return out;
    };
    // Steps as in joint_test.cc (rates ~1, |w| ~ 2): 1e-3 s for the first derivative
    // (error ~1e-13), 3e-3 s for the second (~3e-11).
    const Eigen::VectorXd d1 = test::firstDerivative(along, 1e-3);
    const Eigen::VectorXd d2 = test::secondDerivative(along, 3e-3);
    INFO((flexible ? "flexible" : "rigid")
         << ": rate " << kp.rate.transpose() << " | " << d1.head<3>().transpose() << "; bias "
         << kp.bias.transpose() << " | " << d2.head<3>().transpose());
    CHECK((d1.head<3>() - kp.rate).cwiseAbs().maxCoeff() < 1e-10);
    CHECK((d1.tail<3>() - kv.rate).cwiseAbs().maxCoeff() < 1e-10);
    CHECK((d2.head<3>() - kp.bias).cwiseAbs().maxCoeff() < 1e-8);
    CHECK((d2.tail<3>() - kv.bias).cwiseAbs().maxCoeff() < 1e-8);
    CHECK(kp.bias.norm() > 0.1);  // centripetal terms of |w|^2 0.1 m and more
    // Generalised force of a point force: added to h, equal to G^T f.
    const Eigen::Vector3d f(3.0, -1.0, 2.0);
    Eigen::VectorXd h = Eigen::VectorXd::Constant(6 + nq, 0.5);
    addMarkerForce(body, sp.data(), m, f, h.data());
    CHECK(((h.array() - 0.5).matrix() - kp.G.transpose() * f).cwiseAbs().maxCoeff() < 1e-14);
  }
}
