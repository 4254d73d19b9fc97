// Force elements along a line (runtime/forces/line_force.h, spring_damper.h,
// hertz_point_contact.h) on small synthetic bodies, directly: action and reaction, the
// generalised forces as the negative gradient of the potential energy (difference quotients
// along exact motions, tests/support/body_motion.h), Hertz's law and its energy, no force
// apart, and the damping force proportional to the rate.
#include "runtime/forces/line_force.h"

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "common/base/error.h"
#include "runtime/bodies/floating_body.h"
#include "runtime/bodies/marker_kinematics.h"
#include "runtime/forces/hertz_point_contact.h"
#include "runtime/forces/spring_damper.h"
#include "tests/support/body_motion.h"
#include "tests/support/synthetic_bodies.h"

using namespace ffriga;

namespace {

struct TestBody {
  std::shared_ptr<FlexibleBodySid> sid;
  std::unique_ptr<FloatingBody3d> model;
  BodyMarker marker;
  Eigen::VectorXd sp, sv;
};

// A rigid body with an off-centre centre of mass, or the spring body of synthetic_bodies.h
// (4 modes) with a marker with random translation modes (~0.05 m per unit q); frame at r,
// rotated at random, q ~ 1e-2; velocities v ~ 0.5 m/s, w ~ 2 rad/s, qdot ~ 1/s.
TestBody makeBody(std::mt19937& gen, bool flexible, const Eigen::Vector3d& r,
                  const Eigen::Vector3d& x0) {
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
    b.marker.Psi = Eigen::MatrixXd::Zero(3, nq);  // force elements use points only
  }
  b.sp.resize(7 + nq);
  b.sp << r, test::randomQuaternion(gen), test::randomMatrix(gen, nq, 1, 1e-2);
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

Eigen::Vector3d markerAt(const TestBody& b, const Eigen::VectorXd& sp) {
  MarkerKinematics k;
  markerPoint(*b.model, sp.data(), b.sv.data(), b.marker, k);
  return k.value;
}

// Shifts body b's frame so that its marker is at distance l from point Ra along a random
// direction.
void placeAt(std::mt19937& gen, TestBody& b, const Eigen::Vector3d& Ra, double l) {
  const Eigen::Vector3d n = test::randomMatrix(gen, 3, 1).normalized();
  b.sp.head<3>() += Ra + l * n - markerAt(b, b.sp);
}

// The generalised forces of force element f (end a on the ground if `ga` is null) at the
// positions spa, spb with the velocities sva, svb.
struct Loads {
  Eigen::VectorXd ha, hb;
  LineForceState state;
};
Loads loadsAt(const LineForce& f, const TestBody* ga, const Eigen::VectorXd& spa,
              const Eigen::VectorXd& sva, const TestBody& b, const Eigen::VectorXd& spb,
              const Eigen::VectorXd& svb) {
  Loads out;
  out.ha = Eigen::VectorXd::Zero(ga ? ga->model->numVelocities() : 0);
  out.hb = Eigen::VectorXd::Zero(b.model->numVelocities());
  f.apply(ga ? spa.data() : nullptr, ga ? sva.data() : nullptr, spb.data(), svb.data(),
          ga ? out.ha.data() : nullptr, out.hb.data(), &out.state);
  return out;
}

// Inertial force and moment about the inertial origin of a body's generalised force h
// (rigid part: force and moment about the frame origin, body components).
void inertialLoad(const Eigen::VectorXd& sp, const Eigen::VectorXd& h, Eigen::Vector3d& F,
                  Eigen::Vector3d& M) {
  const Eigen::Matrix3d A = rotationMatrix(sp.data() + 3);
  F = A * h.head<3>();
  M = sp.head<3>().cross(F) + A * h.segment<3>(3);
}

// Hertz spheres of different materials and radii (steel on aluminium), so that a wrong
// combination of E*, R* shows.
const HertzSphere kSteel{2.11e11, 0.3, 0.01, 0.0};
const HertzSphere kAluminium{7.0e10, 0.33, 0.025, 0.0};

// K = 4/3 E* sqrt(R*), written out here independently of common/mechanics/hertz.cc.
double hertzK(const HertzSphere& a, const HertzSphere& b) {
  const double Es = 1.0 / ((1.0 - a.poisson_ratio * a.poisson_ratio) / a.youngs_modulus +
                           (1.0 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus);
  const double Rs = 1.0 / (1.0 / a.radius + 1.0 / b.radius);
  return 4.0 / 3.0 * Es * std::sqrt(Rs);
}

}  // namespace

TEST_CASE("force elements: equal and opposite forces on the line, moments balance", "[forces]") {
  // Between a rigid and a flexible body: the inertial forces on the two sum to zero, their
  // moments about the inertial origin too (the forces act along one line, so the moments of
  // the pair about any point vanish), and the force on b lies along the line from R_a to R_b
  // with the element's tension.
  std::mt19937 gen(21);
  for (const bool hertz : {false, true}) {
    TestBody a = makeBody(gen, false, {0.1, 0.2, -0.1}, {0.05, -0.1, 0.08});
    TestBody b = makeBody(gen, true, {0.0, 0.0, 0.0}, {-0.07, 0.02, 0.11});
    const Eigen::Vector3d Ra = markerAt(a, a.sp);
    placeAt(gen, b, Ra, hertz ? 0.035 - 2e-5 : 0.3);  // Hertz: 20 um approach
    std::unique_ptr<LineForce> f;
    if (hertz)
      f = std::make_unique<HertzPointContact>("h", endOf(a, 0), endOf(b, 1), kSteel, kAluminium);
    else
      f = std::make_unique<SpringDamper>("s", endOf(a, 0), endOf(b, 1), 400.0, 3.0, 0.2);
    const Loads L = loadsAt(*f, &a, a.sp, a.sv, b, b.sp, b.sv);
    Eigen::Vector3d Fa, Ma, Fb, Mb;
    inertialLoad(a.sp, L.ha, Fa, Ma);
    inertialLoad(b.sp, L.hb, Fb, Mb);
    const Eigen::Vector3d d = markerAt(b, b.sp) - Ra;
    INFO(f->kind() << ": tension " << L.state.tension << " N, F_a " << Fa.transpose() << ", F_b "
                   << Fb.transpose() << ", moment sum " << (Ma + Mb).transpose());
    CHECK(std::abs(L.state.tension) > 10.0);  // a real load (spring ~40 N, Hertz ~600 N)
    // Round-off of forces |T| through two rotations: a few eps |T|; of moments at arms of
    // ~0.3 m: a few eps |T| 0.3 m.
    const double T = std::abs(L.state.tension);
    CHECK((Fa + Fb).norm() < 1e-14 * T);
    CHECK((Ma + Mb).norm() < 1e-14 * T);
    CHECK((Fb + L.state.tension * d.normalized()).norm() < 1e-14 * T);  // -T n on end b
    CHECK(std::abs(L.state.length - d.norm()) < 1e-15);
  }
}

TEST_CASE("force elements: the generalised forces are minus the gradient of the energy",
          "[forces]") {
  // For the conservative elements (undamped spring, Hertz) and every velocity coordinate k of
  // either body (translations, rotations, elastic coordinates), move that body's positions
  // along the exact motion with unit velocity e_k: then dV/dt = -h_k (the power of the
  // element's forces is minus the rate of its energy).
  std::mt19937 gen(22);
  for (const bool hertz : {false, true}) {
    for (const bool ground : {false, true}) {
      TestBody a = makeBody(gen, true, {0.1, 0.2, -0.1}, {0.05, -0.1, 0.08});
      TestBody b = makeBody(gen, true, {0.0, 0.0, 0.0}, {-0.07, 0.02, 0.11});
      const Eigen::Vector3d Ra = ground ? Eigen::Vector3d(0.3, -0.2, 0.1) : markerAt(a, a.sp);
      const double approach = 2e-5;  // Hertz: 20 um, forces ~600 N
      placeAt(gen, b, Ra, hertz ? 0.035 - approach : 0.3);
      const MarkerEnd ea = ground ? groundEnd(Ra) : endOf(a, 0);
      std::unique_ptr<LineForce> f;
      if (hertz)
        f = std::make_unique<HertzPointContact>("h", ea, endOf(b, 1), kSteel, kAluminium);
      else
        f = std::make_unique<SpringDamper>("s", ea, endOf(b, 1), 400.0, 0.0, 0.2);
      const TestBody* ga = ground ? nullptr : &a;
      const Loads L0 = loadsAt(*f, ga, a.sp, a.sv, b, b.sp, b.sv);
      // Steps: the spring's energy varies on the scale of the body (0.1 m), Hertz's on the
      // approach (20 um): 1e-4 and 1e-7 s at unit rates. Spring: truncation ~1e-16 |V| / s,
      // round-off eps |V| / h ~ 1e-11 N. Hertz: truncation h^4 |V^(5)| / 30 ~ 1e-8 N, and the
      // approach R_a + R_b - l carries round-off eps l ~ 8e-18 m, an energy error F eps l ~
      // 5e-15 J, so dV/dt is good to ~5e-8 N at h = 1e-7 s (seen: 1e-7 N of ~600 N).
      const double h = hertz ? 1e-7 : 1e-4;
      double worst = 0.0, largest = 0.0;
      for (const bool onA : {true, false}) {
        if (onA && ground) continue;
        const TestBody& body = onA ? a : b;
        const Eigen::VectorXd& hk = onA ? L0.ha : L0.hb;
        for (int k = 0; k < body.model->numVelocities(); ++k) {
          const Eigen::VectorXd ek = Eigen::VectorXd::Unit(body.model->numVelocities(), k);
          auto energy = [&](double t) {
            const Eigen::VectorXd spa = onA ? test::flowPositions(a.sp, ek, t) : a.sp;
            const Eigen::VectorXd spb = onA ? b.sp : test::flowPositions(b.sp, ek, t);
            const double V = loadsAt(*f, ga, spa, a.sv, b, spb, b.sv).state.energy;
            return Eigen::VectorXd(Eigen::VectorXd::Constant(1, V));
          };
          const double dV = test::firstDerivative(energy, h)(0);
          worst = std::max(worst, std::abs(dV + hk(k)));
          largest = std::max(largest, std::abs(hk(k)));
        }
      }
      INFO(f->kind() << (ground ? " from the ground" : " between bodies") << ": tension "
                     << L0.state.tension << " N, largest generalised force " << largest
                     << ", worst |dV/dt + h_k| " << worst);
      CHECK(largest > 10.0);
      // The difference quotients' accuracy above, relative to the loads (~40 N and ~600 N):
      // a margin of ~5 for Hertz.
      CHECK(worst < 1e-9 * largest);
    }
  }
}

TEST_CASE("Hertz point contact: F = K delta^(3/2), energy 2/5 K delta^(5/2), none apart",
          "[forces]") {
  std::mt19937 gen(23);
  TestBody a = makeBody(gen, false, {0.1, 0.2, -0.1}, {0.0, 0.0, 0.0});
  TestBody b = makeBody(gen, false, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0});
  const HertzPointContact hc("h", endOf(a, 0), endOf(b, 1), kSteel, kAluminium);
  const double K = hertzK(kSteel, kAluminium);
  // The formula evaluated in another order: a few ulps.
  CHECK(hc.stiffness() == Approx(K).epsilon(1e-14));
  const double radii = kSteel.radius + kAluminium.radius;
  CHECK(hc.radiusSum() == radii);
  const Eigen::Vector3d Ra = markerAt(a, a.sp);
  for (const double delta : {1e-7, 3e-6, 2e-5, 1e-4}) {
    placeAt(gen, b, Ra, radii - delta);
    const Loads L = loadsAt(hc, &a, a.sp, a.sv, b, b.sp, b.sv);
    // The placement loses digits of the 0.035 m length: |error| ~ eps 0.035 ~ 1e-17 m,
    // relative 1e-10 of the smallest approach. The law is then checked at the approach dl of
    // the reported length, to a few ulps.
    const double dl = radii - L.state.length;
    INFO("delta " << delta << " m: tension " << L.state.tension << " N, energy " << L.state.energy
                  << " J");
    CHECK(dl == Approx(delta).epsilon(1e-9));
    CHECK(L.state.tension == Approx(-K * std::pow(dl, 1.5)).epsilon(1e-14));  // pushes apart
    CHECK(L.state.energy == Approx(0.4 * K * std::pow(dl, 2.5)).epsilon(1e-14));
    // The force on b points away from a.
    Eigen::Vector3d Fb, Mb;
    inertialLoad(b.sp, L.hb, Fb, Mb);
    CHECK(Fb.dot(markerAt(b, b.sp) - Ra) > 0.0);
    // No damping: the rate does not enter.
    const Loads L2 = loadsAt(hc, &a, a.sp, 3.0 * a.sv, b, b.sp, -b.sv);
    CHECK(L2.state.rate != L.state.rate);
    CHECK(L2.state.tension == L.state.tension);
  }
  // Apart (and just touching): no force, no energy; h is left untouched bit for bit.
  for (const double gap : {0.0, 1e-9, 0.01}) {
    placeAt(gen, b, Ra, radii + gap);
    Loads L = loadsAt(hc, &a, a.sp, a.sv, b, b.sp, b.sv);
    if (gap == 0.0 && L.state.length < radii) continue;  // placement round-off inside
    CHECK(L.state.tension == 0.0);
    CHECK(L.state.energy == 0.0);
    CHECK(L.ha.isZero(0.0));
    CHECK(L.hb.isZero(0.0));
  }
}

TEST_CASE("spring-damper: T = k (l - l0) + c dl/dt, the rate is dl/dt, damping dissipates",
          "[forces]") {
  // Between a rigid and a flexible body moving at random: the reported rate equals dl/dt by
  // difference quotients along the exact motion, the tension is k (l - l0) + c dl/dt, so the
  // damping part scales with the rate (reversed velocities reverse it), and the power of the
  // element's forces is -dV/dt - c (dl/dt)^2.
  std::mt19937 gen(24);
  const double k = 400.0, c = 3.0, l0 = 0.2;
  TestBody a = makeBody(gen, false, {0.1, 0.2, -0.1}, {0.05, -0.1, 0.08});
  TestBody b = makeBody(gen, true, {0.0, 0.0, 0.0}, {-0.07, 0.02, 0.11});
  const Eigen::Vector3d Ra = markerAt(a, a.sp);
  placeAt(gen, b, Ra, 0.3);
  const SpringDamper s("s", endOf(a, 0), endOf(b, 1), k, c, l0);
  const Loads L = loadsAt(s, &a, a.sp, a.sv, b, b.sp, b.sv);
  auto along = [&](double t) {
    const Eigen::VectorXd spa = test::flowPositions(a.sp, a.sv, t);
    const Eigen::VectorXd spb = test::flowPositions(b.sp, b.sv, t);
    const LineForceState st = loadsAt(s, &a, spa, a.sv, b, spb, b.sv).state;
    return Eigen::VectorXd(Eigen::Vector2d(st.length, st.energy));
  };
  // Step 1e-3 s at rates ~1 m/s and w ~ 2 rad/s on lengths ~0.3 m: truncation
  // h^4 |l^(5)| / 30 ~ 1e-13 m/s, round-off eps / h ~ 1e-13.
  const Eigen::Vector2d rates = test::firstDerivative(along, 1e-3);
  const double ldot = rates(0), Vdot = rates(1);
  INFO("rate " << L.state.rate << " m/s, dl/dt " << ldot << " m/s; tension " << L.state.tension
               << " N");
  CHECK(std::abs(ldot) > 0.05);  // the bodies do move along the line
  CHECK(std::abs(L.state.rate - ldot) < 1e-10);
  // Tension from length and rate: round-off of terms ~40 N.
  CHECK(std::abs(L.state.tension - (k * (L.state.length - l0) + c * L.state.rate)) < 1e-12);
  // Reversed velocities: the rate and the damping force change sign, the elastic part stays.
  Eigen::VectorXd sva = -a.sv, svb = -b.sv;
  const Loads R = loadsAt(s, &a, a.sp, sva, b, b.sp, svb);
  CHECK(R.state.rate == Approx(-L.state.rate).epsilon(1e-14));
  CHECK((L.state.tension - R.state.tension) == Approx(2.0 * c * L.state.rate).epsilon(1e-12));
  // Power balance: h . z = -dV/dt - c (dl/dt)^2 (the damper only takes energy out).
  const double power = L.ha.dot(a.sv) + L.hb.dot(b.sv);
  CHECK(std::abs(power + Vdot + c * ldot * ldot) < 1e-9);  // ~1e-11 quotients, ~10 W terms
  // Coincident points have no line of action: two rigid bodies at one place, markers at
  // their frame origins.
  TestBody c1 = makeBody(gen, false, {0.1, 0.2, -0.1}, Eigen::Vector3d::Zero());
  TestBody c2 = makeBody(gen, false, {0.1, 0.2, -0.1}, Eigen::Vector3d::Zero());
  const SpringDamper s0("s0", endOf(c1, 0), endOf(c2, 1), k, c, l0);
  CHECK_THROWS_AS(loadsAt(s0, &c1, c1.sp, c1.sv, c2, c2.sp, c2.sv), ComputeError);
}
