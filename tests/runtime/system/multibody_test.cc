// Rigid multibody systems against analytical solutions (issue 9): pendulum periods, energy
// and constraint conservation, joint reactions, spring-dampers and Hertz's point contact.
// Scenes are written inline and need no SID files (rigid bodies are given in the scene).
#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include "common/mechanics/hertz.h"
#include "runtime/integration/bdf_integrator.h"
#include "runtime/scene/scene.h"

using namespace ffriga;

namespace {

Scene sceneFromText(const std::string& text) {
  return buildScene(parseYamlText(text, "inline.yaml"), {},
                    [](const std::string& p, SidContent) -> FlexibleBodySid {
                      throw InputError("no SID files in this test: " + p);
                    });
}

// Complete elliptic integral of the first kind K(k) by the arithmetic-geometric mean:
// K = pi / (2 AGM(1, sqrt(1 - k^2))), converging quadratically to round-off.
double ellipticK(double k) {
  double a = 1.0, b = std::sqrt(1.0 - k * k);
  for (int i = 0; i < 40 && std::abs(a - b) > 1e-16 * a; ++i) {
    const double an = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = an;
  }
  return M_PI / (2.0 * a);
}

IntegratorOptions tightOptions(const Scene& s, double rtol) {
  IntegratorOptions o = s.settings.integrator;
  o.rtol = rtol;
  o.atol *= rtol / 1e-6;
  o.max_order = 5;  // no stiffness here: the highest order is the most accurate
  return o;
}

// A horizontal rod-like rigid body of length 2 L along x, pinned at its left end
// (x = -L in body coordinates) by a revolute joint about y to the ground at the origin;
// its centre starts at (L, 0, 0): 90 degrees away from hanging.
const char* kPendulum = R"(
gravity: [0, 0, -9.81]
bodies:
  - name: bob
    rigid: {mass: 2.0, inertia: [[0.001, 0, 0], [0, 0.03, 0], [0, 0, 0.03]]}
    position: [0.4, 0, 0]
    markers: [{name: pivot, position: [-0.4, 0, 0]}]
joints:
  - name: hinge
    type: revolute
    a: {body: ground, position: [0, 0, 0]}
    b: {body: bob, marker: pivot}
    axis: [0, 1, 0]
integrator: {end_time: 1.0, output_interval: 0.01}
)";

}  // namespace

TEST_CASE("rigid pendulum released at 90 degrees: period from the complete elliptic integral",
          "[multibody]") {
  Scene s = sceneFromText(kPendulum);
  MultibodySystem& sys = *s.system;
  const double m = 2.0, L = 0.4, g = 9.81, Ic = 0.03;
  const double Ipivot = Ic + m * L * L;
  // T = 4 sqrt(I / (m g L)) K(sin(theta0 / 2)), theta0 = pi / 2.
  const double T = 4.0 * std::sqrt(Ipivot / (m * g * L)) * ellipticK(std::sin(M_PI / 4.0));
  BdfIntegrator integ(sys, 0.0, s.y0, tightOptions(s, 1e-11));
  integ.setStopTime(T);
  const int wy = sys.velocityOffset(0) + 4;  // angular velocity about y (body components)
  // Half a period: the swing ends at the other horizontal, where w_y changes sign.
  double t = 0.0, tPrev = 0.0;
  Eigen::VectorXd y(sys.size());
  while (t < 0.25 * T) {  // w_y keeps its sign until T / 2
    tPrev = t;
    t = integ.step();
  }
  double wPrev;
  integ.interpolate(tPrev, y);
  wPrev = y(wy);
  for (;;) {
    integ.interpolate(t, y);
    if ((y(wy) > 0) != (wPrev > 0)) break;
    tPrev = t;
    wPrev = y(wy);
    t = integ.step();
    REQUIRE(t < T);
  }
  // Bisection on the step's interpolating polynomial.
  double lo = tPrev, hi = t;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    integ.interpolate(mid, y);
    ((y(wy) > 0) == (wPrev > 0) ? lo : hi) = mid;
  }
  const double period = lo + hi;  // twice the half period
  INFO("period " << period << " s, exact " << T << " s, relative error " << period / T - 1.0);
  CHECK(std::abs(period / T - 1.0) < 1e-6);  // the issue's bound
}

TEST_CASE("undamped rigid double pendulum conserves energy and its constraints", "[multibody]") {
  // Two links of length 0.3 m (centres at their middles), joined by revolute joints about y:
  // ground - upper (its top) and upper (bottom) - lower (top); released at 90 and 30 degrees.
  Scene s = sceneFromText(R"(
gravity: [0, 0, -9.81]
bodies:
  - name: upper
    rigid: {mass: 1.0, inertia: [[0.0075, 0, 0], [0, 0.0075, 0], [0, 0, 0.0001]]}
    position: [0, 0, -0.15]
    markers: [{name: top, position: [0, 0, 0.15]}, {name: bottom, position: [0, 0, -0.15]}]
  - name: lower
    rigid: {mass: 0.5, inertia: [[0.00375, 0, 0], [0, 0.00375, 0], [0, 0, 0.00005]]}
    position: [0, 0, -0.45]
    markers: [{name: top, position: [0, 0, 0.15]}]
joints:
  - {name: shoulder, type: revolute, a: {body: ground}, b: {body: upper, marker: top},
     axis: [0, 1, 0], initial_angle: 1.5707963267948966}
  - {name: elbow, type: revolute, a: {body: upper, marker: bottom}, b: {body: lower, marker: top},
     axis: [0, 1, 0], initial_angle: 0.5235987755982988}
integrator: {end_time: 2.0, output_interval: 0.01}
)");
  MultibodySystem& sys = *s.system;
  // Initial angles assembled: the upper link horizontal along -x... rotation about +y by
  // 90 degrees takes -z to -x; the lower link 30 degrees further.
  const Eigen::Vector3d r1 = s.y0.segment<3>(sys.positionOffset(0));
  const Eigen::Vector3d r2 = s.y0.segment<3>(sys.positionOffset(1));
  CHECK((r1 - Eigen::Vector3d(-0.15, 0, 0)).norm() < 1e-15);
  const double phi = M_PI / 2 + M_PI / 6;  // absolute angle of the lower link
  CHECK((r2 - Eigen::Vector3d(-0.3 - 0.15 * std::sin(phi), 0, -0.15 * std::cos(phi))).norm() <
        1e-15);

  BdfIntegrator integ(sys, 0.0, s.y0, tightOptions(s, 1e-11));
  const SystemEnergies e0 = sys.energies(s.y0.data());
  const double E0 = e0.kinetic + e0.gravity;
  double worstEnergy = 0.0, worstPosition = 0.0, maxKinetic = 0.0;
  Eigen::VectorXd y(sys.size());
  ConstraintRows rows;
  for (int k = 1; k <= 200; ++k) {
    integ.advance(0.01 * k, y);
    const SystemEnergies e = sys.energies(y.data());
    maxKinetic = std::max(maxKinetic, e.kinetic);
    worstEnergy = std::max(worstEnergy, std::abs(e.kinetic + e.gravity - E0));
    sys.constraintRows(integ.currentState().data(), rows);
    for (int i = 0; i < rows.g.size(); ++i)
      if (i % 5 < 3) worstPosition = std::max(worstPosition, std::abs(rows.g(i)));  // point rows
  }
  INFO("energy drift " << worstEnergy << " J of " << maxKinetic << " J kinetic; position "
                       << "violation " << worstPosition << " m");
  CHECK(maxKinetic > 1.0);                 // it did swing (about 2.2 J of gravity energy released)
  CHECK(worstEnergy < 1e-8 * maxKinetic);  // the issue's bound, relative to the energy exchanged
  CHECK(worstPosition <= 1e-10);           // the issue's bound (m)
}

TEST_CASE("joint reactions: a hanging body's weight; no moment about a revolute axis",
          "[multibody]") {
  SECTION("at rest under a spherical joint the reaction carries the weight") {
    Scene s = sceneFromText(R"(
gravity: [0, 0, -9.81]
bodies:
  - name: weight
    rigid: {mass: 3.0, centre_of_mass: [0, 0, -0.2], inertia: [[0.01, 0, 0], [0, 0.02, 0], [0, 0, 0.03]]}
    position: [0.1, 0.2, 0.3]
    markers: [{name: hook, position: [0, 0, 0]}]
joints:
  - {type: spherical, a: {body: ground}, b: {body: weight, marker: hook}}
integrator: {end_time: 0.1, output_interval: 0.01}
)");
    const std::vector<JointReaction> r = s.system->jointReactions(s.y0.data());
    REQUIRE(r.size() == 1);
    CHECK((r[0].force - Eigen::Vector3d(0, 0, 3.0 * 9.81)).norm() < 1e-12 * 30.0);
    CHECK(r[0].moment.norm() < 1e-12 * 30.0);  // a spherical joint carries no moment
    Eigen::VectorXd ydot(s.system->size());
    s.system->rhs(0.0, s.y0.data(), ydot.data());
    CHECK(ydot.tail(6).norm() < 1e-12);  // at rest, it stays at rest
  }
  SECTION("a swinging pendulum's revolute reaction has no moment about the axis") {
    Scene s = sceneFromText(kPendulum);
    MultibodySystem& sys = *s.system;
    BdfIntegrator integ(sys, 0.0, s.y0, tightOptions(s, 1e-8));
    Eigen::VectorXd y(sys.size());
    double worst = 0.0, largest = 0.0;
    for (int k = 1; k <= 50; ++k) {
      integ.advance(0.02 * k, y);
      const JointReaction r = sys.jointReactions(y.data())[0];
      worst = std::max(worst, std::abs(r.moment(1)));  // the axis stays the inertial y axis
      largest = std::max(largest, r.force.norm());
    }
    CHECK(largest > 2.0 * 9.81);          // the hinge pulls more than the weight while it swings
    CHECK(worst < 1e-9 * largest * 0.4);  // round-off of moments of ~ force x 0.4 m
  }
}

TEST_CASE("spring-damper: a mass on a vertical spring oscillates at sqrt(k/m) about its sag",
          "[multibody]") {
  // k = 400 N/m, m = 1 kg, free length 0.2 m: static sag m g / k = 0.024525 m. Released
  // 1 cm below the equilibrium; the vertical motion is z(t) = z_eq - 0.01 cos(w t).
  Scene s = sceneFromText(R"(
gravity: [0, 0, -9.81]
bodies:
  - name: mass
    rigid: {mass: 1.0, inertia: [[0.001, 0, 0], [0, 0.001, 0], [0, 0, 0.001]]}
    position: [0, 0, -0.234525]
    markers: [{name: eye, position: [0, 0, 0]}]
force_elements:
  - {name: spring, type: spring_damper, a: {body: ground, position: [0, 0, 0]},
     b: {body: mass, marker: eye}, stiffness: 400.0, free_length: 0.2}
joints:
  - {name: guide, type: prismatic, a: {body: ground, position: [0, 0, 0]},
     b: {body: mass, marker: eye}, axis: [0, 0, 1]}
integrator: {end_time: 1.0, output_interval: 0.01}
)");
  MultibodySystem& sys = *s.system;
  BdfIntegrator integ(sys, 0.0, s.y0, tightOptions(s, 1e-11));
  const double w = std::sqrt(400.0), zeq = -0.2 - 9.81 / 400.0;
  Eigen::VectorXd y(sys.size());
  double worst = 0.0;
  for (int k = 1; k <= 100; ++k) {
    const double t = 0.01 * k;
    integ.advance(t, y);
    worst = std::max(worst, std::abs(y(2) - (zeq - 0.01 * std::cos(w * t))));
  }
  INFO("largest deviation " << worst << " m");
  CHECK(worst < 1e-9);  // 1e-7 of the amplitude: the integrator's tolerance
  const std::vector<LineForceState> f = sys.lineForceStates(y.data());
  CHECK(std::abs(f[0].tension - 400.0 * (f[0].length - 0.2)) < 1e-9);
}

TEST_CASE("Hertz point contact between rigid spheres reproduces Hertz's impact", "[multibody]") {
  // Two steel spheres r = 1 cm (m = 0.032882 kg) meet head-on at 0.1 m/s each.
  const double R = 0.01, rho = 7850.0, m = rho * 4.0 / 3.0 * M_PI * R * R * R;
  const double I = 0.4 * m * R * R;
  const std::string body = "rigid: {mass: " + std::to_string(m) + ", inertia: [[" +
                           std::to_string(I) + ", 0, 0], [0, " + std::to_string(I) +
                           ", 0], [0, 0, " + std::to_string(I) + "]]}";
  Scene s = sceneFromText(R"(
bodies:
  - name: a
    )" + body + R"(
    position: [0, 0, 0]
    velocity: [0.1, 0, 0]
    markers: [{name: centre, position: [0, 0, 0]}]
  - name: b
    )" + body + R"(
    position: [0.020001, 0, 0]
    velocity: [-0.1, 0, 0]
    markers: [{name: centre, position: [0, 0, 0]}]
force_elements:
  - name: hertz
    type: hertz_contact
    a: {body: a, marker: centre}
    b: {body: b, marker: centre}
    spheres: [{radius: 0.01, youngs_modulus: 2.11e11, poisson_ratio: 0.3},
              {radius: 0.01, youngs_modulus: 2.11e11, poisson_ratio: 0.3}]
integrator: {end_time: 1.0e-4, output_interval: 1.0e-7}
)");
  MultibodySystem& sys = *s.system;
  const HertzSphere hs{2.11e11, 0.3, R, std::stod(std::to_string(m))};
  const HertzImpact h = hertzImpact(hs, hs, 0.2);
  IntegratorOptions o = s.settings.integrator;
  o.rtol = 1e-10;
  o.atol *= 1e-4;
  BdfIntegrator integ(sys, 0.0, s.y0, o);
  Eigen::VectorXd y(sys.size());
  double fmax = 0.0;
  for (int k = 1; k <= 1000; ++k) {
    integ.advance(1e-7 * k, y);
    fmax = std::max(fmax, -sys.lineForceStates(y.data())[0].tension);
  }
  INFO("maximum force " << fmax << " N, Hertz " << h.max_force << " N");
  // Sampled every 0.1 us near a smooth maximum (curvature F_max (pi / T)^2): the sampling
  // error is below 1e-5 relative.
  CHECK(std::abs(fmax / h.max_force - 1.0) < 1e-5);
  // Elastic: the spheres leave at their approach speed.
  CHECK(std::abs(y(sys.velocityOffset(0)) + 0.1) < 1e-6);
}
