// Flexible rods with joints against beam theory (issue 9): the rod of the Sect. 7 pendulums
// (configs/bodies/rod.yaml: Craig-Bampton with its joint markers on the interface; and
// rod_modal.yaml: 20 free-free modes, as in the paper), preprocessed in-process, hanging from
// a pin or clamped horizontally, in static equilibrium by the static preload.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include <catch2/catch.hpp>

#include <omp.h>
#include <unistd.h>
#include <filesystem>

#include "common/sid/sid_file.h"
#include "preproc/input/body_config.h"
#include "preproc/body_preprocessor.h"
#include "preproc/reduction/marker_points.h"
#include "runtime/integration/bdf_integrator.h"
#include "runtime/scene/scene.h"
#include "tests/support/test_util.h"

using namespace ffriga;

namespace {

const FlexibleBodySid& rodSid(const std::string& stem) {
  static std::map<std::string, FlexibleBodySid> cache;
  auto it = cache.find(stem);
  if (it == cache.end()) {
    // One thread: igaprep's OpenMP assembly is not yet bitwise reproducible across thread
    // schedules (issue 13), and the bounds below are tight enough to notice its last bits.
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    PreprocessSummary summary;
    const BodyConfig c =
        loadBodyConfig(std::string(FFRIGA_SOURCE_DIR) + "/configs/bodies/" + stem + ".yaml");
    it = cache.emplace(stem, preprocessBody(c, nullptr, &summary)).first;
    omp_set_num_threads(threads);
  }
  return it->second;
}

// The rods' SID files, written once per test run into a private temporary folder and read
// back by the scene loader (the file round trip of igaprep -o and ffrsim).
std::string sidFolder() {
  static const std::string dir = [] {
    const auto d = std::filesystem::temp_directory_path() /
                   ("ffriga_flexible_rod_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    for (const char* stem : {"rod", "rod_modal"})
      writeSid(rodSid(stem), (d / (std::string(stem) + ".sid.h5")).string());
    return d.string();
  }();
  return dir;
}

// The scene "lives" in the SID folder, so that SID names never resolve against the working
// directory (where the sid.* tests leave SID files of their own).
Scene rodScene(const std::string& text) {
  return buildScene(
      parseYamlText(text, sidFolder() + "/inline.yaml"), {sidFolder()},
      [](const std::string& path, SidContent content) { return readSid(path, content); });
}

// The simple flexible pendulum (configs/scenes/pendulum_flexible.yaml over 10 ms): the rod
// hanging from a revolute suspension at 19 degrees, a rigid bob welded to its lower end, in
// static equilibrium; `rodKey` an extra key of the rod's entry (e.g. "quasi_static: false").
std::string pendulumScene(const std::string& rodKey = "") {
  return std::string(R"(
gravity: [0, 0, -9.81]
static_preload: true
bodies:
  - {name: rod, sid: rod.sid.h5, position: [0, 0, -0.05])") +
         (rodKey.empty() ? "" : ", " + rodKey) + R"(}
  - name: bob
    rigid:
      mass: 0.03288200310757317
      inertia: [[1.315280124302927e-06, 0, 0], [0, 1.315280124302927e-06, 0], [0, 0, 1.315280124302927e-06]]
    position: [0, 0, -0.11]
    markers: [{name: top, position: [0, 0, 0.01]}]
joints:
  - {name: suspension, type: revolute, a: {body: ground, position: [0, 0, 0]},
     b: {body: rod, marker: top}, axis: [0, 1, 0], initial_angle: 0.33161255787892263}
  - {name: weld, type: fixed, a: {body: rod, marker: bottom}, b: {body: bob, marker: top}}
integrator: {end_time: 0.01, output_interval: 0.001, rtol: 1.0e-8, atol_position: 1.0e-13,
             atol_velocity: 1.0e-10}
)";
}

// Steel rod: E, rho, radius, length of configs/bodies/rod.yaml.
constexpr double kE = 2.11e11, kRho = 7850.0, kR = 0.002, kL = 0.1, kG = 9.81;

// Inertial position of sensor `s` at y.
Eigen::Vector3d sensorAt(MultibodySystem& sys, const Eigen::VectorXd& y, int s) {
  Eigen::Vector3d x, v;
  sys.sensorState(y.data(), s, x, v);
  return x;
}

}  // namespace

TEST_CASE("marker rotation operators are exact for rigid motions", "[flexible]") {
  // Control point "modes" that are the rigid motions themselves: columns 0-2 translations
  // u_k = e_c, columns 3-5 rotations u_k = theta x x_k (Phi_k = -x_k~). A marker's rotation
  // Psi q must then be theta exactly and zero for translations, for point markers
  // (1/2 curl) and face markers (least-squares fit) alike: NURBS reproduce rigid fields.
  const BodyConfig c = loadBodyConfig(std::string(FFRIGA_SOURCE_DIR) + "/configs/bodies/rod.yaml");
  const HierarchicalSpace space = bodySpace(c);
  const Eigen::MatrixXd& P = space.controlPoints();
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(3 * P.rows(), 6);
  for (int k = 0; k < P.rows(); ++k) {
    const Eigen::Vector3d x = P.row(k).transpose();
    Phi.block<3, 3>(3 * k, 0).setIdentity();
    Phi.block<3, 3>(3 * k, 3) << 0.0, x(2), -x(1), -x(2), 0.0, x(0), x(1), -x(0), 0.0;
  }
  Eigen::MatrixXd expected(3, 6);
  expected << Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Identity();
  const Eigen::MatrixXd point = markerRotationModes(space, "p", {0.3, 0.6, 0.7}, Phi);
  CHECK((point - expected).cwiseAbs().maxCoeff() < 1e-9);  // gradients of ~1e3 /m: round-off
  for (const bool upper : {false, true}) {
    const Marker face = evaluateFaceMarker(space, "f", 2, upper, 5, Phi);
    CHECK((face.Psi - expected).cwiseAbs().maxCoeff() < 1e-9);
    CHECK(std::abs(face.values.sum() - 1.0) < 1e-14);  // area means: partition of unity
    CHECK(std::abs(face.position(2) - (upper ? kL : 0.0)) < 1e-14);
    CHECK(face.position.head<2>().norm() < 1e-14);  // the centroid of the disk
  }
}

TEST_CASE("rod hanging from a pin: static elongation under its own weight", "[flexible]") {
  for (const std::string stem : {"rod", "rod_modal"}) {
    Scene s = rodScene(R"(
gravity: [0, 0, -9.81]
static_preload: true
bodies:
  - {name: rod, sid: )" +
                       stem + R"(.sid.h5, position: [0, 0, -0.05]}
joints:
  - {name: pin, type: spherical, a: {body: ground}, b: {body: rod, marker: top}}
sensors:
  - {name: tip, body: rod, marker: bottom}
integrator: {end_time: 0.01, output_interval: 0.001}
)");
    MultibodySystem& sys = *s.system;
    // A bar under its own weight: delta = rho g L^2 / (2 E).
    const double exact = kRho * kG * kL * kL / (2.0 * kE);
    const double delta = -(sensorAt(sys, s.y0, 0)(2) + kL);
    INFO(stem << ": elongation " << delta << " m, bar theory " << exact << " m; preload "
              << s.preload.iterations << " Newton steps");
    if (stem == "rod") {
      CHECK(std::abs(delta / exact - 1.0) < 0.01);  // the issue's bound
    } else {
      // The free-free modes of the modal rod (the paper's reduction) miss most of the static
      // axial stretch that a load at the end face causes: the reason configs/bodies/rod.yaml
      // uses Craig-Bampton with interface face markers. Reported, not bounded.
      WARN(stem << ": elongation " << 100.0 * (delta / exact - 1.0) << " % from bar theory");
    }
    // At rest in equilibrium: the pin carries the weight, nothing accelerates.
    const std::vector<JointReaction> r = sys.jointReactions(s.y0.data());
    CHECK(std::abs(r[0].force(2) / (sys.body(0).sid().mass * kG) - 1.0) < 1e-8);  // as below
    Eigen::VectorXd ydot(sys.size());
    sys.rhs(0.0, s.y0.data(), ydot.data());
    const int nq = sys.body(0).nq();
    const Eigen::VectorXd qdd = ydot.segment(sys.velocityOffset(0) + 6, nq);
    const Eigen::VectorXd kq =
        sys.body(0).sid().Ke.diagonal().cwiseProduct(s.y0.segment(sys.positionOffset(0) + 7, nq));
    CHECK(qdd.lpNorm<Eigen::Infinity>() <= 1e-10 * kq.lpNorm<Eigen::Infinity>());
    if (stem == "rod") {
      // No ringing: hanging at rest, the elastic energy keeps its preload value.
      BdfIntegrator integ(sys, 0.0, s.y0, s.settings.integrator);
      const double e0 = sys.energies(s.y0.data()).elastic;
      Eigen::VectorXd y(sys.size());
      double worst = 0.0;
      for (int k = 1; k <= 10; ++k) {
        integ.advance(1e-3 * k, y);
        worst = std::max(worst, std::abs(sys.energies(y.data()).elastic / e0 - 1.0));
      }
      INFO("elastic energy " << e0 << " J, largest relative change over 10 ms " << worst);
      CHECK(worst < 1e-6);  // the issue's bound
    }
  }
}

TEST_CASE("horizontal rod clamped at one end: tip deflection against beam theory", "[flexible]") {
  // The rod along +x (its axis z turned onto x by a rotation of +90 degrees about y),
  // clamped at its top marker to the ground by a fixed joint; gravity -z.
  // Euler-Bernoulli: delta = q L^4 / (8 E I), q = rho A g, I = pi r^4 / 4, A = pi r^2;
  // shear (Timoshenko) adds about 0.1 % for L / r = 50.
  const double A = M_PI * kR * kR, I = M_PI * std::pow(kR, 4) / 4.0;
  const double exact = kRho * A * kG * std::pow(kL, 4) / (8.0 * kE * I);
  for (const std::string stem : {"rod", "rod_modal"}) {
    Scene s = rodScene(R"(
gravity: [0, 0, -9.81]
static_preload: true
bodies:
  - {name: rod, sid: )" +
                       stem + R"(.sid.h5, position: [0.05, 0, 0],
     orientation: [0.7071067811865476, 0, -0.7071067811865476, 0]}
joints:
  - {name: clamp, type: fixed, a: {body: ground}, b: {body: rod, marker: top}}
sensors:
  - {name: tip, body: rod, marker: bottom}
integrator: {end_time: 0.01, output_interval: 0.001}
)");
    MultibodySystem& sys = *s.system;
    const Eigen::Vector3d tip = sensorAt(sys, s.y0, 0);
    const double delta = -tip(2);
    INFO(stem << ": tip at " << tip.transpose() << ", deflection " << delta << " m, beam theory "
              << exact << " m (" << 100.0 * (delta / exact - 1.0) << " %)");
    CHECK(std::abs(tip(0) - kL) < 1e-6);  // the top marker at the origin, tip at +L
    if (stem == "rod") {
      CHECK(std::abs(delta / exact - 1.0) < 0.01);  // the issue's bound
    }
    WARN(stem << ": cantilever tip deflection " << 100.0 * (delta / exact - 1.0) << " %");
    // Reactions at the clamp: the weight and its moment m g L / 2 about y.
    const double m = sys.body(0).sid().mass;
    const JointReaction r = sys.jointReactions(s.y0.data())[0];
    // To 1e-8: the preload is polished to round-off (measured 1e-10 and 0 for the two
    // rods; with its former stop at 1e-10 of the elastic forces, the elastic, and so rigid,
    // accelerations left were up to 2.8e-8 of g, depending on the machine's BLAS kernels).
    // The moment also carries the geometric effect of the deflection on the lever arm,
    // O((delta / L)^2) = 2e-9 (measured 7e-10).
    CHECK(std::abs(r.force(2) / (m * kG) - 1.0) < 1e-8);
    // The reaction balances the weight's moment +m g L / 2 about y.
    CHECK(std::abs(r.moment(1) / (-m * kG * kL / 2.0) - 1.0) < 1e-8);
  }
}

TEST_CASE("joint equations: J is dg/dt and the bias completes d2g/dt2 on flexible markers",
          "[flexible]") {
  // For every joint type between the flexible rod's face marker and a rigid body, at a
  // random state (rotated, spinning at a few rad/s, elastically moving):
  // g(y + e ydot) - g(y - e ydot) = 2 e J z and J z(y +- e ydot) differences give
  // J dz/dt + bias, by central differences along the flow (relative error O(e^2) ~ 1e-8
  // of the largest term).
  for (const bool frozen : {true, false})
    for (const char* type : {"spherical", "revolute", "fixed", "prismatic"}) {
      const std::string axis = std::string(type) == "revolute" || std::string(type) == "prismatic"
                                   ? ", axis: [0.3, 0.8, 0.5]"
                                   : "";
      Scene s = rodScene(std::string(R"(
gravity: [0, 0, -9.81]
bodies:
  - {name: rod, sid: rod.sid.h5, position: [0, 0, -0.05], frozen: )") +
                         (frozen ? "true" : "false") + R"(}
  - name: bob
    rigid: {mass: 0.03, inertia: [[1e-6, 0, 0], [0, 2e-6, 0], [0, 0, 2.5e-6]]}
    position: [0, 0, -0.11]
    markers: [{name: top, position: [0, 0, 0.01]}]
joints:
  - {name: j, type: )" + type +
                         ", a: {body: rod, marker: bottom}, b: {body: bob, marker: top}" + axis +
                         R"(}
integrator: {end_time: 0.01, output_interval: 0.001}
)");
      MultibodySystem& sys = *s.system;
      Eigen::VectorXd y = s.y0;
      test::rng().seed(7);
      const int nq = sys.body(0).nq();
      for (int i = 0; i < nq; ++i) {
        // Elastic motion of micrometres at up to MHz: elastic accelerations ~1e6 (SI), so that
        // the difference quotients below stay accurate.
        y(sys.positionOffset(0) + 7 + i) = 1e-9 * test::uniform(-1, 1);
        y(sys.velocityOffset(0) + 6 + i) = 1e-3 * test::uniform(-1, 1);
      }
      for (int b = 0; b < 2; ++b) {
        for (int i = 0; i < 6; ++i) y(sys.velocityOffset(b) + i) = test::uniform(-2, 2);
        for (int i = 0; i < 4; ++i) y(sys.positionOffset(b) + 3 + i) += 0.3 * test::uniform(-1, 1);
        sys.body(b).normalize(y.data() + sys.positionOffset(b));
      }
      Eigen::VectorXd ydot(sys.size());
      sys.rhs(0.0, y.data(), ydot.data());
      // Central differences along the flow with Richardson extrapolation (4 D(e/2) - D(e)) / 3,
      // which removes the O(e^2) error that the MHz elastic rates would otherwise leave.
      const int v0 = sys.velocityOffset(0), nv = sys.size() - v0;
      ConstraintRows r0;
      sys.constraintRows(y.data(), r0);
      auto differences = [&](double e, Eigen::VectorXd& gdot, Eigen::VectorXd& gddot) {
        const Eigen::VectorXd yp = y + e * ydot, ym = y - e * ydot;
        ConstraintRows rp, rm;
        sys.constraintRows(yp.data(), rp);
        sys.constraintRows(ym.data(), rm);
        gdot = (rp.g - rm.g) / (2 * e);
        gddot = (rp.J * yp.tail(nv) - rm.J * ym.tail(nv)) / (2 * e);
      };
      Eigen::VectorXd g1, gg1, g2, gg2;
      differences(1e-6, g1, gg1);
      differences(0.5e-6, g2, gg2);
      const Eigen::VectorXd gdot = (4.0 * g2 - g1) / 3.0, gddot = (4.0 * gg2 - gg1) / 3.0;
      const Eigen::VectorXd z = y.tail(nv), Jz = r0.J * z;
      const Eigen::VectorXd model = r0.J * ydot.tail(nv) + r0.bias;
      INFO((frozen ? "frozen " : "flexible ")
           << type << ": dg/dt " << gdot.transpose() << " | J z " << Jz.transpose());
      CHECK((gdot - Jz).norm() <= 1e-7 * (Jz.norm() + 1e-12));
      INFO(type << ": d2g/dt2 " << gddot.transpose() << " | J zdot + bias " << model.transpose());
      const double scale = (r0.J * ydot.tail(nv)).norm() + r0.bias.norm();  // the terms cancel
      CHECK((gddot - model).norm() <= 1e-6 * scale);
    }
}

TEST_CASE("flexible pendulum: no ringing after the static preload", "[flexible]") {
  // The rod with a rigid bob (configs/scenes/pendulum_flexible.yaml) released at 19 degrees
  // in static equilibrium. While it swings the loads change (gravity across the rod, the
  // centrifugal pull), so its elastic energy changes too (+3.5e-4 in 10 ms); without ringing
  // it follows the quasi-static solution, the preload of the state reached. Checked at
  // 2, 5 and 10 ms: the elastic energy within 3e-5 of the quasi-static one (measured
  // 3e-7 to 6.3e-6; a ringing at the amplitude of the static deflection would be ~1).
  Scene s = rodScene(pendulumScene());
  MultibodySystem& sys = *s.system;
  BdfIntegrator integ(sys, 0.0, s.y0, s.settings.integrator);
  const double e0 = sys.energies(s.y0.data()).elastic;
  Eigen::VectorXd y(sys.size());
  for (const double t : {0.002, 0.005, 0.01}) {
    integ.advance(t, y);
    sys.projectState(y.data());
    Eigen::VectorXd yq = y;
    staticPreload(sys, yq);
    const double e = sys.energies(y.data()).elastic, eq = sys.energies(yq.data()).elastic;
    INFO("t = " << t << " s: elastic energy " << e << " J (" << e / e0 - 1.0
                << " from the preload), quasi-static " << eq << " J");
    CHECK(std::abs(e / eq - 1.0) < 3e-5);  // measured <= 6.3e-6: the dynamic lag
    CHECK(std::abs(e / e0 - 1.0) > 1e-6);  // the loads did change: the check is not void
  }
}

TEST_CASE("quasi-static coordinates with joints: the joints hold the dynamic motion", "[flexible]") {
  // schemas/multibody.md "Joints and quasi-static coordinates": the default rule applies to
  // jointed bodies; the joints' equations have zero columns on the quasi-static coordinates
  // (the markers' Phi and Psi without them, kept aside for the offset); the quasi-static
  // coordinates follow the constrained accelerations (a_s = 0 after the projection); and
  // with no damping the swinging pendulum keeps its energy.
  Scene off = rodScene(pendulumScene("quasi_static: false"));
  CHECK(off.system->body(0).quasiStatic().empty());

  Scene s = rodScene(pendulumScene());
  MultibodySystem& sys = *s.system;
  const BodyModel& rod = sys.body(0);
  const QuasiStaticModes& qs = rod.quasiStatic();
  REQUIRE(!qs.empty());  // default rule: above 4 x the rod's lowest elastic frequency
  INFO(qs.size() << " quasi-static coordinates above " << qs.cutoff_hz << " Hz");

  // Zero columns of the joint equations on the quasi-static coordinates, and the modes kept
  // aside at both of the rod's joint ends (nonzero: the interface modes move the faces).
  ConstraintRows rows;
  sys.constraintRows(s.y0.data(), rows);
  const int c0 = rod.numRigidVelocities();  // the rod is body 0: its columns come first
  double kept = 0.0;
  for (const int i : qs.index) CHECK(rows.J.col(c0 + i).isZero(0.0));
  for (int j = 0; j < sys.numJoints(); ++j)
    for (int e = 0; e < 2; ++e)
      if (sys.joint(j).end(e).body == 0) kept += sys.joint(j).end(e).quasi_static_Phi.norm();
  CHECK(kept > 0.0);
  // ... and not on the dynamic ones (the joints do hold the rod's low modes).
  double dynamic = 0.0;
  for (int i = 0; i < rod.nq(); ++i)
    if (std::find(qs.index.begin(), qs.index.end(), i) == qs.index.end())
      dynamic += rows.J.col(c0 + i).norm();
  CHECK(dynamic > 0.0);

  BdfIntegrator integ(sys, 0.0, s.y0, s.settings.integrator);
  const SystemEnergies e0 = sys.energies(s.y0.data());
  const double total0 = e0.kinetic + e0.gravity + e0.elastic;
  Eigen::VectorXd y(sys.size()), ydot(sys.size());
  for (const double t : {0.005, 0.01}) {
    integ.advance(t, y);
    REQUIRE(sys.projectState(y.data()));
    // The quasi-static manifold of the constrained accelerations: the rates of q_s are
    // a_s / (k tau), so k tau dq_s/dt = a_s; against the elastic force k q_s of the same
    // coordinates (the projection converges to 1e-9 of the displacements).
    sys.rhs(t, y.data(), ydot.data());
    const int p0 = sys.positionOffset(0) + rod.numRigidPositions();
    double as = 0.0, force = 0.0;
    for (int j = 0; j < qs.size(); ++j) {
      const int i = qs.index[j];
      as = std::max(as, std::abs(qs.stiffness(j) * qs.tau * ydot(p0 + i)));
      force = std::max(force, std::abs(qs.stiffness(j) * y(p0 + i)));
    }
    INFO("t = " << t << " s: |a_s| " << as << ", |k q_s| " << force);
    CHECK(force > 0.0);
    CHECK(as <= 1e-6 * force);
    // No damping acts (the rod's damped modes, above 9 kHz, are all quasi-static), so the
    // energy stays: 1e-10 J of the ~4e-3 J exchanged (the integrator's error at rtol 1e-8).
    const SystemEnergies e = sys.energies(y.data());
    const double total = e.kinetic + e.gravity + e.elastic;
    INFO("energy change " << total - total0 << " J, kinetic " << e.kinetic << " J");
    CHECK(std::abs(total - total0) <= 1e-10);
  }
}
