// Joints (runtime/constraints/joint.h) on small synthetic bodies, directly: the equations'
// count and meaning at assembled configurations, J z and the bias against difference
// quotients of g along exact motions (tests/support/body_motion.h), and the reactions the
// system reports against the balance of momentum and against a pendulum's release.
#include "runtime/constraints/joint.h"

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "runtime/bodies/marker_kinematics.h"
#include "runtime/system/multibody_system.h"
#include "tests/support/body_motion.h"
#include "tests/support/synthetic_bodies.h"

using namespace ffriga;

namespace {

constexpr JointType kTypes[] = {JointType::kSpherical, JointType::kRevolute, JointType::kFixed,
                                JointType::kPrismatic};

// One body of a test: its model, a marker and a state.
struct TestBody {
  std::shared_ptr<FlexibleBodySid> sid;
  std::unique_ptr<FloatingBody3d> model;
  BodyMarker marker;
  Eigen::VectorXd sp, sv;
};

// A rigid body with its centre of mass off the frame origin (so that m c~ couples), or the
// spring body of synthetic_bodies.h with 4 modes and a marker with random translation and
// rotation modes (Phi ~ 0.05 m, Psi ~ 0.5 rad per unit q). Random state: a rotated frame,
// v ~ 0.5 m/s, w ~ 2 rad/s, q ~ 1e-2, qdot ~ 1/s (elastic rates of the marker ~ 0.05 m/s, as
// large as the rigid ones, so that a wrong elastic column shows).
TestBody makeBody(std::mt19937& gen, bool flexible, const Eigen::Vector3d& x0) {
  TestBody b;
  if (flexible) {
    b.sid = std::make_shared<FlexibleBodySid>(test::springBody(4, 2e3));
  } else {
    b.sid = std::make_shared<FlexibleBodySid>(test::rigidBody(1.7, {0.02, 0.03, 0.04}));
    b.sid->first_moment = 1.7 * Eigen::Vector3d(0.03, -0.02, 0.01);
  }
  b.model = std::make_unique<FloatingBody3d>(flexible ? "flexible" : "rigid", b.sid);
  const int nq = b.model->nq();
  b.marker = fixedMarker("m", x0);
  if (flexible) {
    b.marker.Phi = test::randomMatrix(gen, 3, nq, 0.05);
    b.marker.Psi = test::randomMatrix(gen, 3, nq, 0.5);
  }
  b.sp.resize(7 + nq);
  b.sp << test::randomMatrix(gen, 3, 1, 0.3), test::randomQuaternion(gen),
      test::randomMatrix(gen, nq, 1, 1e-2);
  b.sv.resize(6 + nq);
  b.sv << test::randomMatrix(gen, 3, 1, 0.5), test::randomMatrix(gen, 3, 1, 2.0),
      test::randomMatrix(gen, nq, 1, 1.0);
  return b;
}

MarkerEnd endOf(const TestBody& b, int index) {
  MarkerEnd e;
  e.body = index;
  e.model = b.model.get();
  e.marker = b.marker;
  return e;
}

MarkerEnd groundEnd(const Eigen::Vector3d& x) {
  MarkerEnd e;
  e.marker = fixedMarker("ground", x);
  return e;
}

// The pairings of the tests: end a on the ground, a rigid or a flexible body; end b rigid or
// flexible.
enum class Pairing { kGroundRigid, kGroundFlexible, kRigidFlexible, kFlexibleFlexible };
constexpr Pairing kPairings[] = {Pairing::kGroundRigid, Pairing::kGroundFlexible,
                                 Pairing::kRigidFlexible, Pairing::kFlexibleFlexible};
const char* pairingName(Pairing p) {
  switch (p) {
    case Pairing::kGroundRigid:
      return "ground-rigid";
    case Pairing::kGroundFlexible:
      return "ground-flexible";
    case Pairing::kRigidFlexible:
      return "rigid-flexible";
    case Pairing::kFlexibleFlexible:
      return "flexible-flexible";
  }
  return "?";
}
bool groundA(Pairing p) {
  return p == Pairing::kGroundRigid || p == Pairing::kGroundFlexible;
}
bool flexibleA(Pairing p) {
  return p == Pairing::kFlexibleFlexible;
}
bool flexibleB(Pairing p) {
  return p != Pairing::kGroundRigid;
}

void setRotation(Eigen::VectorXd& sp, const Eigen::Matrix3d& A) {
  const Eigen::Quaterniond p(A);
  sp.segment<4>(3) << p.w(), p.x(), p.y(), p.z();
}

// Inertial position of a marker point, and direction of a marker vector u0, at positions sp.
Eigen::Vector3d markerAt(const FloatingBody3d& body, const BodyMarker& m,
                         const Eigen::VectorXd& sp) {
  MarkerKinematics k;
  const Eigen::VectorXd sv = Eigen::VectorXd::Zero(body.numVelocities());
  markerPoint(body, sp.data(), sv.data(), m, k);
  return k.value;
}
Eigen::Vector3d markerDirection(const FloatingBody3d& body, const BodyMarker& m,
                                const Eigen::VectorXd& sp, const Eigen::Vector3d& u0) {
  MarkerKinematics k;
  const Eigen::VectorXd sv = Eigen::VectorXd::Zero(body.numVelocities());
  markerVector(body, sp.data(), sv.data(), m, u0, k);
  return k.value;
}
Eigen::Vector3d markerAt(const TestBody& b, const Eigen::VectorXd& sp) {
  return markerAt(*b.model, b.marker, sp);
}

}  // namespace

TEST_CASE("joints: J z is dg/dt and the bias is d2g/dt2 along exact motions", "[joint]") {
  std::mt19937 gen(11);
  for (const Pairing pairing : kPairings) {
    for (const JointType type : kTypes) {
      TestBody a = makeBody(gen, flexibleA(pairing), {0.05, -0.1, 0.08});
      TestBody b = makeBody(gen, flexibleB(pairing), {-0.07, 0.02, 0.11});
      const bool ground = groundA(pairing);
      Joint joint("j", type, ground ? groundEnd({0.2, -0.1, 0.3}) : endOf(a, 0),
                  endOf(b, ground ? 0 : 1));
      const Eigen::Matrix3d E = test::randomRotation(gen);
      joint.setAxes(E, rotationMatrix(a.sp.data() + 3), rotationMatrix(b.sp.data() + 3));
      JointRows rows;
      joint.evaluate(a.sp.data(), a.sv.data(), b.sp.data(), b.sv.data(), rows);
      const int m = joint.numEquations();
      REQUIRE(rows.g.size() == m);
      REQUIRE(rows.bias.size() == m);
      REQUIRE(rows.Ja.rows() == m);
      REQUIRE(rows.Jb.rows() == m);
      REQUIRE(rows.Ja.cols() == (ground ? 0 : a.model->numVelocities()));  // none for the ground
      REQUIRE(rows.Jb.cols() == b.model->numVelocities());
      // g along the motion of both bodies under their constant velocities.
      auto g = [&](double t) {
        const Eigen::VectorXd spa = test::flowPositions(a.sp, a.sv, t);
        const Eigen::VectorXd spb = test::flowPositions(b.sp, b.sv, t);
        JointRows r;
        joint.evaluate(spa.data(), a.sv.data(), spb.data(), b.sv.data(), r);
        return r.g;
      };
      Eigen::VectorXd Jz = rows.Jb * b.sv;
      if (!ground) Jz += rows.Ja * a.sv;
      // Step 1e-3 s: truncation h^4 |g^(5)| / 30 with |g^(5)| ~ |w|^5 0.5 m (|w| up to
      // 3.5 rad/s: ~300 m/s^5) ~ 1e-11, round-off ~ eps |g| / h ~ 1e-13 (seen: 3e-11). Rates
      // are ~1 m/s, so 2e-10 is 2e-10 relative.
      const Eigen::VectorXd gdot = test::firstDerivative(g, 1e-3);
      // Step 3e-3 s balances truncation h^4 |g^(6)| / 90 ~ 1e-9 and round-off
      // 5 eps |g| / h^2 ~ 1e-11 (seen: 2e-9); biases are ~ |w|^2 0.5 m ~ 2-6 m/s^2, so 1e-8 is
      // still a few 1e-9 relative.
      const Eigen::VectorXd gddot = test::secondDerivative(g, 3e-3);
      INFO(pairingName(pairing) << " " << jointTypeName(type) << "\n  dg/dt   " << gdot.transpose()
                                << "\n  J z     " << Jz.transpose() << "\n  d2g/dt2 "
                                << gddot.transpose() << "\n  bias    " << rows.bias.transpose());
      CHECK((gdot - Jz).cwiseAbs().maxCoeff() < 2e-10);
      CHECK((gddot - rows.bias).cwiseAbs().maxCoeff() < 1e-8);
      // The motion is general: the checks above compared non-trivial numbers.
      CHECK(Jz.norm() > 0.1);
      CHECK(rows.bias.norm() > 0.1);
    }
  }
}

TEST_CASE("joints: g = 0 when assembled, and zero exactly along the motions each type allows",
          "[joint]") {
  // Assemble each pairing with the markers' points on each other and the frame E in both
  // bodies: then every equation vanishes. Moving body b relative to a by the motions the joint
  // allows keeps g = 0; the others give the values of the header's equations: a shift s e1
  // gives d = s e1 (spherical, revolute, fixed) or U(a1).d = s (prismatic); a rotation by
  // alpha about e_i turns b's frame, so U(a2).U(b3) = -sin(alpha) for i = 1 (revolute, fixed,
  // prismatic), U(a3).U(b1) = -sin(alpha) for i = 2 and U(a1).U(b2) = -sin(alpha) for i = 3
  // (fixed, prismatic).
  std::mt19937 gen(12);
  const int expected[] = {3, 5, 6, 5};
  for (const Pairing pairing : kPairings) {
    for (int t = 0; t < 4; ++t) {
      const JointType type = kTypes[t];
      TestBody a = makeBody(gen, flexibleA(pairing), {0.05, -0.1, 0.08});
      TestBody b = makeBody(gen, flexibleB(pairing), {-0.07, 0.02, 0.11});
      // Elastic coordinates in the null space of the marker's Psi: the marker is displaced
      // (Phi q != 0) but not rotated, so the frames stay aligned exactly.
      for (TestBody* body : {&a, &b}) {
        if (body->model->nq() == 0) continue;
        const Eigen::MatrixXd N = Eigen::FullPivLU<Eigen::MatrixXd>(body->marker.Psi).kernel();
        body->sp.tail(body->model->nq()) = 0.02 * N.col(0).normalized();
        REQUIRE((body->marker.Phi * body->sp.tail(body->model->nq())).norm() > 1e-4);
      }
      const bool ground = groundA(pairing);
      const Eigen::Vector3d Ra = ground ? Eigen::Vector3d(0.2, -0.1, 0.3) : markerAt(a, a.sp);
      // Body b's frame origin placed so that its marker point is Ra.
      b.sp.head<3>() += Ra - markerAt(b, b.sp);
      const Eigen::Matrix3d E = test::randomRotation(gen);
      Joint joint("j", type, ground ? groundEnd(Ra) : endOf(a, 0), endOf(b, ground ? 0 : 1));
      joint.setAxes(E, rotationMatrix(a.sp.data() + 3), rotationMatrix(b.sp.data() + 3));
      INFO(pairingName(pairing) << " " << jointTypeName(type));
      CHECK(joint.numEquations() == expected[t]);
      auto gOf = [&](const Eigen::VectorXd& spb) {
        JointRows r;
        joint.evaluate(a.sp.data(), a.sv.data(), spb.data(), b.sv.data(), r);
        return r.g;
      };
      // Round-off of coordinates ~0.3 m and of unit vectors: a few 1e-16; 1e-14 is safe.
      const double tol = 1e-14;
      CHECK(gOf(b.sp).cwiseAbs().maxCoeff() < tol);
      // Rigid motions of body b relative to a about b's marker point (inertial axes E_i).
      auto rotated = [&](int axis, double angle) {
        Eigen::VectorXd sp = b.sp;
        const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, E.col(axis)).toRotationMatrix();
        setRotation(sp, R * rotationMatrix(b.sp.data() + 3));
        sp.head<3>() = Ra + R * (b.sp.head<3>() - Ra);
        return sp;
      };
      auto shifted = [&](int axis, double s) {
        Eigen::VectorXd sp = b.sp;
        sp.head<3>() += s * E.col(axis);
        return sp;
      };
      const double s = 0.03, alpha = 0.4;
      const Eigen::VectorXd gShift1 = gOf(shifted(0, s)), gShift3 = gOf(shifted(2, s));
      const Eigen::VectorXd gRot[3] = {gOf(rotated(0, alpha)), gOf(rotated(1, alpha)),
                                       gOf(rotated(2, alpha))};
      if (type != JointType::kPrismatic) {
        // d = R_b - R_a in inertial components.
        CHECK((gShift1.head<3>() - s * E.col(0)).cwiseAbs().maxCoeff() < tol);
        CHECK((gShift3.head<3>() - s * E.col(2)).cwiseAbs().maxCoeff() < tol);
        if (expected[t] > 3)  // the frames' rows: untouched by a shift
          CHECK(gShift1.tail(expected[t] - 3).cwiseAbs().maxCoeff() < tol);
      } else {
        CHECK(std::abs(gShift1(0) - s) < tol);  // U(a1).d
        CHECK(gShift1.tail(4).cwiseAbs().maxCoeff() < tol);
        CHECK(gShift3.cwiseAbs().maxCoeff() < tol);  // sliding along e3 is free
      }
      if (type == JointType::kSpherical) {
        for (const Eigen::VectorXd& gr : gRot) CHECK(gr.cwiseAbs().maxCoeff() < tol);
      } else if (type == JointType::kRevolute) {
        CHECK(gRot[2].cwiseAbs().maxCoeff() < tol);  // turning about e3 is free
        CHECK(gRot[0].head<3>().cwiseAbs().maxCoeff() < tol);
        CHECK(std::abs(gRot[0](3)) < tol);                    // U(a1).U(b3)
        CHECK(std::abs(gRot[0](4) + std::sin(alpha)) < tol);  // U(a2).U(b3)
        CHECK(std::abs(gRot[1](3) - std::sin(alpha)) < tol);  // e3 turned towards e1
        CHECK(std::abs(gRot[1](4)) < tol);
      } else {
        const int r0 = type == JointType::kFixed ? 3 : 2;  // first rotational row
        for (int i = 0; i < 3; ++i) {
          Eigen::Vector3d expectedRot = Eigen::Vector3d::Zero();
          expectedRot(i) = -std::sin(alpha);
          CHECK((gRot[i].segment<3>(r0) - expectedRot).cwiseAbs().maxCoeff() < tol);
          CHECK(gRot[i].head(r0).cwiseAbs().maxCoeff() < tol);  // the marker point stays put
        }
      }
    }
  }
}

TEST_CASE("joint reactions: the load on body b balances its momentum, for every type", "[joint]") {
  // One body joined to the ground, in a general moving state under gravity. Its momentum
  // changes only by gravity and the joint's load (F at the marker point R_b, moment M):
  //   dP/dt = m g + F,   dH/dt = r_c x m g + R_b x F + M   (H about the inertial origin,
  //   r_c the centre of mass). dP/dt and dH/dt by difference quotients of the body's momentum
  // along the system's own rates ydot: an independent check of reaction()'s reduction of
  // Jb^T lambda to a force and a moment (with elastic coordinates, whose load is internal).
  std::mt19937 gen(13);
  const Eigen::Vector3d gravity(0.0, 0.0, -9.81);
  for (const bool flexible : {false, true}) {
    for (const JointType type : kTypes) {
      TestBody tb = makeBody(gen, flexible, {-0.07, 0.02, 0.11});
      const BodyMarker marker = tb.marker;
      const Eigen::VectorXd sp = tb.sp, sv = tb.sv;
      const Eigen::Vector3d R0 = markerAt(tb, sp);
      MultibodySystem sys;
      sys.setGravity(gravity);
      const int b = sys.addBody(std::move(tb.model));
      const auto& body = static_cast<const FloatingBody3d&>(sys.body(b));
      MarkerEnd eb;
      eb.body = b;
      eb.model = &body;
      eb.marker = marker;
      auto joint = std::make_unique<Joint>("j", type, groundEnd(R0), eb);
      const Eigen::Matrix3d E = test::randomRotation(gen);
      const Eigen::Matrix3d A = rotationMatrix(sp.data() + 3);
      joint->setAxes(E, Eigen::Matrix3d::Identity(), A);
      sys.addJoint(std::move(joint));
      Eigen::VectorXd y(sys.size());
      y << sp, sv;
      const JointReaction r = sys.jointReactions(y.data())[0];
      Eigen::VectorXd ydot(sys.size());
      sys.rhs(0.0, y.data(), ydot.data());
      auto momentumAt = [&](double t) {
        const Eigen::VectorXd yt = y + t * ydot;
        Eigen::Vector3d L, H;
        body.momentum(yt.data(), yt.data() + body.numPositions(), L, H);
        Eigen::VectorXd out(6);
        out << L, H;
        return out;
      };
      // Step 1e-5 s against rates of up to ~1e3 /s (elastic frequencies ~ 100 rad/s,
      // accelerations ~ 10-100 SI): truncation h^4 |P^(5)| / 30 below 1e-11 N, round-off
      // eps |P| / h ~ 1e-11 N.
      const Eigen::VectorXd rate = test::firstDerivative(momentumAt, 1e-5);
      const FloatingBody3d::Invariants inv = body.invariants(sp.tail(body.nq()));
      const double m = body.sid().mass;
      const Eigen::Vector3d rc = sp.head<3>() + A * inv.mc / m;
      const Eigen::Vector3d F = rate.head<3>() - m * gravity;
      const Eigen::Vector3d M = rate.tail<3>() - rc.cross(m * gravity) - R0.cross(F);
      INFO((flexible ? "flexible " : "rigid ")
           << jointTypeName(type) << "\n  reported force " << r.force.transpose() << " moment "
           << r.moment.transpose() << "\n  balance  force " << F.transpose() << " moment "
           << M.transpose());
      // Loads of ~10-100 N and moments ~1-10 N m: 1e-8 N (N m) is the difference quotients'
      // accuracy with a margin of ~100.
      CHECK((r.force - F).cwiseAbs().maxCoeff() < 1e-8);
      CHECK((r.moment - M).cwiseAbs().maxCoeff() < 1e-8);
      CHECK(r.force.norm() > 1.0);  // the joint does carry a load
      // What each type cannot transmit, to round-off of loads ~10 N at arms ~0.1 m: a spherical
      // joint no moment, a revolute one no moment about body b's axis U(b3) (through its
      // marker's rotation Psi q), a prismatic one no force along the ground's e3.
      const Eigen::Vector3d b3 = markerDirection(body, marker, sp, A.transpose() * E.col(2));
      if (type == JointType::kSpherical) CHECK(r.moment.norm() < 1e-12);
      if (type == JointType::kRevolute) CHECK(std::abs(r.moment.dot(b3)) < 1e-12);
      if (type == JointType::kPrismatic) CHECK(std::abs(r.force.dot(E.col(2))) < 1e-12);
      // The frames are set at this state; a flexible marker's rotation Psi q turns b's axes.
      if (!flexible) CHECK(r.violation < 1e-14);  // a few ulps of the unit axes
    }
  }
}

TEST_CASE("joint reactions: a horizontal rod pendulum at release and a cantilevered body at rest",
          "[joint]") {
  // Rigid rod of mass m, centre of mass at distance L from the pivot, moment of inertia I_c
  // about its centre (axis y): released horizontally from rest it starts with angular
  // acceleration m g L / I_p (I_p = I_c + m L^2), so its centre falls at m g L^2 / I_p and the
  // hinge carries F_z = m g (1 - m L^2 / I_p) and no moment (principal axes).
  const double m = 2.0, L = 0.4, Ic = 0.03, g = 9.81;
  auto sid = std::make_shared<FlexibleBodySid>(test::rigidBody(m, {0.001, Ic, Ic}));
  for (const JointType type : {JointType::kRevolute, JointType::kFixed}) {
    MultibodySystem sys;
    sys.setGravity({0.0, 0.0, -g});
    const int b = sys.addBody(std::make_unique<FloatingBody3d>("rod", sid));
    MarkerEnd eb;
    eb.body = b;
    eb.model = static_cast<const FloatingBody3d*>(&sys.body(b));
    eb.marker = fixedMarker("pivot", {-L, 0.0, 0.0});
    auto joint = std::make_unique<Joint>("hinge", type, groundEnd(Eigen::Vector3d::Zero()), eb);
    // e3 along y (revolute axis); e1, e2 along z, x.
    Eigen::Matrix3d E;
    E << 0, 1, 0, 0, 0, 1, 1, 0, 0;
    joint->setAxes(E, Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity());
    sys.addJoint(std::move(joint));
    Eigen::VectorXd y = Eigen::VectorXd::Zero(sys.size());
    y(0) = L;
    y(3) = 1.0;
    const JointReaction r = sys.jointReactions(y.data())[0];
    // Reactions from a 5 x 5 (6 x 6) Schur complement of entries ~1-100: round-off ~1e-14 of
    // the weight (19.6 N); 1e-12 relative leaves a margin.
    const double tol = 1e-12 * m * g;
    if (type == JointType::kRevolute) {
      const double Ip = Ic + m * L * L;
      INFO("revolute: force " << r.force.transpose() << ", moment " << r.moment.transpose());
      CHECK((r.force - Eigen::Vector3d(0, 0, m * g * (1.0 - m * L * L / Ip))).norm() < tol);
      CHECK(r.moment.norm() < tol * L);
    } else {
      // Clamped at rest: the clamp holds the weight, m g up, and balances the weight's moment
      // about the pivot, (L, 0, 0) x (0, 0, -m g) = (0, m g L, 0).
      INFO("fixed: force " << r.force.transpose() << ", moment " << r.moment.transpose());
      CHECK((r.force - Eigen::Vector3d(0, 0, m * g)).norm() < tol);
      CHECK((r.moment - Eigen::Vector3d(0, -m * g * L, 0)).norm() < tol * L);
      Eigen::VectorXd ydot(sys.size());
      sys.rhs(0.0, y.data(), ydot.data());
      CHECK(ydot.tail(6).norm() < 1e-12);  // held at rest
    }
  }
}
