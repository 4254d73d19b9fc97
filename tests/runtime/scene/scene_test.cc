#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>

#include <catch2/catch.hpp>

#include <filesystem>

#include "common/splines/gauss_legendre.h"
#include "common/input/json_schema.h"
#include "common/splines/refinement.h"
#include "common/input/schemas.h"
#include "common/splines/extracted_surface.h"
#include "runtime/scene/scene.h"
#include "runtime/simulation/output_sampler.h"
#include "runtime/bodies/quasi_static_rule.h"
#include "tests/support/surface_fixtures.h"
#include "tests/support/test_util.h"

using namespace ffriga;

namespace {

// Rigid axisymmetric sphere of radius R (steel): meridian half circle from the bottom pole
// to the top pole (rational quadratic, paper Eq. 19 style), refined near the top pole where
// contact happens. Collocation points at the Greville abscissae with weights = arc-length
// integrals of the basis functions (Gauss quadrature), the meridian weights of sid.h.
FlexibleBodySid rigidSphere2d(double R) {
  const double h = 1.0 / std::sqrt(2.0);
  Eigen::MatrixXd P(5, 2);
  P << 0, -R, R, -R, R, 0, R, R, 0, R;
  Eigen::VectorXd w(5);
  w << 1, h, 1, h, 1;
  NurbsPatch arc({KnotVector({0, 0, 0, 0.5, 0.5, 1, 1, 1}, 2)}, P, w);
  std::vector<double> X;
  for (int k = 1; k < 40; ++k) X.push_back(0.96 + 0.001 * k);
  arc = insertKnots(arc, 0, X);
  FlexibleBodySid sid;
  sid.name = "sphere";
  sid.model = ffriga::ModelKind::kAxisymmetric;
  sid.space_dim = 2;
  sid.mass = 7850.0 * 4.0 / 3.0 * M_PI * R * R * R;
  sid.inertia = Eigen::Matrix3d::Identity() * 0.4 * sid.mass * R * R;
  sid.Me = sid.Ke = sid.De = Eigen::MatrixXd(0, 0);
  sid.Ct = sid.Cr0 = Eigen::MatrixXd(0, 3);
  sid.control_points = arc.points();
  sid.weights = arc.weights();
  sid.Phi = Eigen::MatrixXd(2 * arc.numControlPoints(), 0);
  ContactSurface s = test::bezierExtract(arc, 1.0);
  test::addGrevilleCollocation(arc, s, 0.0);
  const ExtractedSurface surf(s, arc.weights());
  Eigen::VectorXd integral = Eigen::VectorXd::Zero(arc.numControlPoints());
  for (int e = 0; e < surf.numElements(); ++e) {
    const QuadratureRule g = gaussLegendre(6, surf.elementLower(e)(0), surf.elementUpper(e)(0));
    for (std::size_t i = 0; i < g.points.size(); ++i) {
      SurfacePoint sp;
      Eigen::MatrixXd Rb;
      surf.evaluate(e, &g.points[i], arc.points(), 1, sp);
      surf.basis(e, &g.points[i], 0, Rb);
      for (int k = 0; k < surf.numFunctions(e); ++k)
        integral(surf.functions(e)[k]) += Rb(0, k) * sp.dx.norm() * g.weights[i];
    }
  }
  s.collocation_weights = integral;
  sid.surfaces.push_back(s);
  return sid;
}

// The rigid sphere made flexible with nq synthetic modes (timing and balance tests, not a
// physical model): mode j moves the surface control points near the top pole with a smooth
// random pattern; Me = E, Ke = diag(omega_j^2) with omega from 2e5 to 2e7 rad/s, modal
// damping 2 %, Ct = 0 (Buckens-like), so M = diag(m, E).
FlexibleBodySid flexibleSphere2d(double R, int nq) {
  FlexibleBodySid sid = rigidSphere2d(R);
  const int ncp = static_cast<int>(sid.control_points.rows());
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(2 * ncp, nq);
  std::srand(7);
  for (int k = 0; k < ncp; ++k) {
    const double y = sid.control_points(k, 1);
    if (y < 0.9 * R) continue;
    for (int j = 0; j < nq; ++j) {
      // Axial and radial displacements; zero radial motion on the axis.
      Phi(2 * k + 1, j) = 1e-3 * std::cos(0.7 * j * (R - y) / R * 40.0) * std::rand() / RAND_MAX;
      if (sid.control_points(k, 0) > 0.0) Phi(2 * k, j) = 0.3 * Phi(2 * k + 1, j);
    }
  }
  Eigen::VectorXd omega = Eigen::VectorXd::LinSpaced(nq, std::log(2e5), std::log(2e7));
  omega = omega.array().exp();
  sid.Phi = Phi;
  sid.Me = Eigen::MatrixXd::Identity(nq, nq);
  sid.Ke = omega.array().square().matrix().asDiagonal();
  sid.De = (0.04 * omega).asDiagonal();
  sid.Ct = Eigen::MatrixXd::Zero(nq, 3);
  sid.frequencies_hz = omega / (2 * M_PI);
  return sid;
}

// Writes empty placeholder files so that SID resolution finds them; the loader maps the
// resolved path to an in-memory SID.
SidLoader fakeLoader(const FlexibleBodySid& sid) {
  for (const char* f : {"sphere_a.sid.h5", "sphere_b.sid.h5"}) std::ofstream(f) << "fake";
  return [sid](const std::string&, SidContent) { return sid; };
}

const char* kScene = R"(name: rigid_spheres
bodies:
  - name: lower
    sid: sphere_a.sid.h5
    position: [0, 0, 0]
    velocity: [0, 0.1, 0]
  - name: upper
    sid: sphere_b.sid.h5
    position: [0, 0.02001, 0]
    orientation: [0, 1, 0, 0]
    velocity: [0, -0.1, 0]
contacts:
  - bodies: [lower, upper]
    penalty_factor: 1.0e13
integrator:
  end_time: 6.0e-4
  output_interval: 1.0e-5
  rtol: 1.0e-8
)";

// `file`: the result file, one per test case (ctest runs the cases in parallel).
double runSpheres(const FlexibleBodySid& sid, double endTime, double rtol, SimulationReport& r,
                  const std::string& file, LinearSolverKind solver = LinearSolverKind::kAuto) {
  std::string text = kScene;
  Scene scene = buildScene(parseYamlText(text, "scene.yaml"), {}, fakeLoader(sid));
  scene.settings.verbosity = 0;
  scene.settings.end_time = endTime;
  scene.settings.integrator.rtol = rtol;
  scene.settings.integrator.linear_solver = solver;
  const std::string path = file;
  ResultWriter writer(path, outputLayout(*scene.system), "unit test", scene.doc.text, FlushConfig{});
  r = simulate(*scene.system, scene.y0, scene.settings, writer);
  writer.close();
  std::remove(path.c_str());
  return r.figures.wall_time_s;
}

std::string errorOf(const std::string& text, const FlexibleBodySid& sid) {
  try {
    buildScene(parseYamlText(text, "scene.yaml"), {}, fakeLoader(sid));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("scene: two rigid axisymmetric spheres bounce back elastically", "[scene]") {
  const FlexibleBodySid sid = rigidSphere2d(0.01);
  Scene scene = buildScene(parseYamlText(kScene, "scene.yaml"), {}, fakeLoader(sid));
  REQUIRE(scene.system->numBodies() == 2);
  REQUIRE(scene.system->numContacts() == 1);
  scene.settings.verbosity = 0;
  const std::string path = "scene_test_result.h5";
  ResultWriter writer(path, outputLayout(*scene.system), "unit test", scene.doc.text, FlushConfig{});
  const SimulationReport r = simulate(*scene.system, scene.y0, scene.settings, writer);
  writer.close();
  REQUIRE(r.completed);
  REQUIRE(r.figures.max_contact_force > 0.0);
  REQUIRE(r.figures.during.steps > 0);
  REQUIRE(r.figures.after.steps > 0);
  // The final state: velocities exchanged (equal masses, conservative penalty force, no
  // damping), linear momentum zero throughout (equal and opposite forces).
  h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  REQUIRE(f.id() >= 0);
  REQUIRE(h5::readStringAttribute(h5::Context{path}, f.id(), "status") == "completed");
  auto lastRow = [&](const std::string& name, int cols) {
    h5::Handle ds(H5Dopen2(f.id(), name.c_str(), H5P_DEFAULT), H5Dclose);
    h5::Handle space(H5Dget_space(ds.id()), H5Sclose);
    hsize_t dims[2] = {0, 1};
    H5Sget_simple_extent_dims(space.id(), dims, nullptr);
    std::vector<double> all(dims[0] * cols);
    H5Dread(ds.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, all.data());
    return std::vector<double>(all.end() - cols, all.end());
  };
  // Body-frame velocities: the upper sphere is turned (axis along -y), so V = -v_y.
  const double vLower = lastRow("bodies/lower/velocity", 3)[1];
  const double vUpper = -lastRow("bodies/upper/velocity", 3)[1];
  const double fEnd = lastRow("contacts/lower-upper/normal_force", 1)[0];
  INFO("max force " << r.figures.max_contact_force << " N, steps " << r.figures.solver.steps << ", final V " << vLower
                    << ", " << vUpper << " wall " << r.figures.wall_time_s);
  REQUIRE(fEnd == 0.0);
  // Momentum: BDF keeps linear invariants exactly up to the Newton tolerance; 1e-9 m/s.
  REQUIRE(std::abs(vLower + vUpper) < 1e-9);
  // Energy: integration error of rtol 1e-8 over ~400 steps through a stiff contact; the
  // penalty force is conservative, so the rebound speed is the impact speed to 1e-4.
  REQUIRE(std::abs(vLower + 0.1) < 1e-5);
  f.reset();
  std::remove(path.c_str());
}

TEST_CASE("scene: flexible axisymmetric spheres collide and separate", "[scene]") {
  SimulationReport r;
  runSpheres(flexibleSphere2d(0.01, 40), 6.0e-4, 1e-6, r, "scene_test_flexible.h5");
  INFO("max force " << r.figures.max_contact_force << " N, steps " << r.figures.solver.steps << ", wall "
                    << r.figures.wall_time_s << " s");
  REQUIRE(r.completed);
  REQUIRE(r.figures.max_contact_force > 0.0);
  REQUIRE(r.figures.after.steps > 0);
}

TEST_CASE("scene: structured and dense Newton matrices give the same impact", "[scene]") {
  // The Newton matrix only steers the corrector iteration: both runs solve the same
  // equations to the same tolerance, so the force peaks agree to a few rtol (1e-6).
  SimulationReport rs, rd;
  runSpheres(flexibleSphere2d(0.01, 40), 6.0e-4, 1e-6, rs, "scene_test_structured.h5",
             LinearSolverKind::kAuto);
  runSpheres(flexibleSphere2d(0.01, 40), 6.0e-4, 1e-6, rd, "scene_test_dense.h5",
             LinearSolverKind::kEigenDense);
  INFO("structured: " << rs.figures.max_contact_force << " N, " << rs.figures.solver.steps << " steps; dense: "
                      << rd.figures.max_contact_force << " N, " << rd.figures.solver.steps << " steps");
  REQUIRE(rs.completed);
  REQUIRE(rd.completed);
  CHECK(std::abs(rs.figures.max_contact_force / rd.figures.max_contact_force - 1.0) <= 1e-5);
  CHECK(std::abs((rs.figures.contact_end - rs.figures.contact_begin) / (rd.figures.contact_end - rd.figures.contact_begin) - 1.0) <=
        1e-3);  // the ends are step midpoints: steps near separation are ~1e-3 of the duration
}

TEST_CASE("scene: integrator.linear_solver selects the Newton matrix", "[scene]") {
  const FlexibleBodySid sid = rigidSphere2d(0.01);
  const Scene byDefault = buildScene(parseYamlText(kScene, "scene.yaml"), {}, fakeLoader(sid));
  CHECK(byDefault.settings.integrator.linear_solver == LinearSolverKind::kAuto);
  const Scene dense = buildScene(
      parseYamlText(test::replaced(kScene, "  rtol: 1.0e-8", "  rtol: 1.0e-8\n  linear_solver: dense"),
                    "scene.yaml"),
      {}, fakeLoader(sid));
  CHECK(dense.settings.integrator.linear_solver == LinearSolverKind::kEigenDense);
  CHECK_THAT(errorOf(test::replaced(kScene, "  rtol: 1.0e-8", "  rtol: 1.0e-8\n  linear_solver: lu"), sid),
             Catch::Contains("key 'integrator.linear_solver'"));
}

TEST_CASE("scene: structured Jacobian of axisymmetric bodies in contact is the dense one",
          "[scene]") {
  // Axisymmetric bodies have a constant mass matrix and no velocity-quadratic forces, so the
  // structured form (D + U V^T) neglects nothing: it must equal the dense Jacobian,
  // contact stiffness included.
  const FlexibleBodySid sid = flexibleSphere2d(0.01, 12);
  Scene scene = buildScene(parseYamlText(kScene, "scene.yaml"), {}, fakeLoader(sid));
  MultibodySystem& sys = *scene.system;
  Eigen::VectorXd y = scene.y0;
  // Push the upper sphere 1 um into the lower one and deform both a little.
  y(sys.positionOffset(1)) -= 1e-6 + (y(sys.positionOffset(1)) - y(sys.positionOffset(0)) - 0.02);
  for (int b = 0; b < 2; ++b)
    for (int j = 0; j < 12; ++j) y(sys.positionOffset(b) + 1 + j) = 1e-9 * std::cos(j + b);
  const int n = sys.size();
  Eigen::VectorXd f(n);
  sys.rhs(0.0, y.data(), f.data());
  REQUIRE(sys.lastRhsContacts()[0].active_points > 0);
  const Eigen::VectorXd scale = Eigen::VectorXd::Ones(n);
  Eigen::MatrixXd Jd = Eigen::MatrixXd::Zero(n, n);
  REQUIRE(sys.jacobian(0.0, y.data(), f.data(), scale.data(), Jd.data()));
  StructuredJacobian Js;
  REQUIRE(sys.structuredJacobian(0.0, y.data(), scale.data(), Js));
  // Dense: one-sided quotients of the linear elastic forces (exact to round-off ~1e-16
  // |Ke| / 1.5e-8) and M^-1 by LDLT; structured: exact diagonals and M^-1 by the Schur
  // formula. 1e-7 of the largest entry (~omega_max^2 = 4e14) covers both.
  CHECK((Js.dense() - Jd).cwiseAbs().maxCoeff() <= 1e-7 * Jd.cwiseAbs().maxCoeff());
}

TEST_CASE("scene: quasi-static coordinates in the structured and dense Jacobians", "[scene]") {
  // With the upper half of the spectrum quasi-static, both Jacobians carry the relaxation
  // rows d/dt q_s = a_s / (k_s tau) (quasi_static_modes.h) and must agree as without; the
  // rates themselves are a_s / (k_s tau) and 0, with a_s the dynamic acceleration.
  const FlexibleBodySid sid = flexibleSphere2d(0.01, 12);
  const std::string text = test::replaced(
      test::replaced(kScene, "    sid: sphere_a.sid.h5\n",
              "    sid: sphere_a.sid.h5\n    quasi_static: {above_first_elastic: 3}\n"),
      "    sid: sphere_b.sid.h5\n", "    sid: sphere_b.sid.h5\n    quasi_static: {above_first_elastic: 3}\n");
  Scene scene = buildScene(parseYamlText(text, "scene.yaml"), {}, fakeLoader(sid));
  const std::string dynamic = test::replaced(
      test::replaced(kScene, "    sid: sphere_a.sid.h5\n", "    sid: sphere_a.sid.h5\n    quasi_static: false\n"),
      "    sid: sphere_b.sid.h5\n", "    sid: sphere_b.sid.h5\n    quasi_static: false\n");
  Scene plain = buildScene(parseYamlText(dynamic, "scene.yaml"), {}, fakeLoader(sid));
  REQUIRE(plain.system->body(0).quasiStatic().empty());
  MultibodySystem& sys = *scene.system;
  const QuasiStaticModes& qs = sys.body(0).quasiStatic();
  REQUIRE(qs.size() > 0);
  REQUIRE(qs.size() < 12);
  Eigen::VectorXd y = scene.y0;
  y(sys.positionOffset(1)) -= 1e-6 + (y(sys.positionOffset(1)) - y(sys.positionOffset(0)) - 0.02);
  for (int b = 0; b < 2; ++b)
    for (int j = 0; j < 12; ++j) {
      y(sys.positionOffset(b) + 1 + j) = 1e-9 * std::cos(j + b);
      if (!std::count(qs.index.begin(), qs.index.end(), j))
        y(sys.velocityOffset(b) + 1 + j) = 1e-6 * std::sin(j + b);
    }
  const int n = sys.size();
  Eigen::VectorXd f(n), fd(n);
  sys.rhs(0.0, y.data(), f.data());
  plain.system->rhs(0.0, y.data(), fd.data());
  REQUIRE(sys.lastRhsContacts()[0].active_points > 0);
  for (int b = 0; b < 2; ++b) {
    const int p0 = sys.positionOffset(b) + 1, v0 = sys.velocityOffset(b) + 1;
    for (int s = 0; s < qs.size(); ++s) {
      const int i = qs.index[s];
      CHECK(f(p0 + i) == fd(v0 + i) / (qs.stiffness(s) * qs.tau));
      CHECK(f(v0 + i) == 0.0);
    }
  }
  const Eigen::VectorXd scale = Eigen::VectorXd::Ones(n);
  Eigen::MatrixXd Jd = Eigen::MatrixXd::Zero(n, n);
  REQUIRE(sys.jacobian(0.0, y.data(), f.data(), scale.data(), Jd.data()));
  StructuredJacobian Js;
  REQUIRE(sys.structuredJacobian(0.0, y.data(), scale.data(), Js));
  CHECK(Js.f_index.size() == 2 * qs.index.size());
  // As in the test above, per row: the quasi-static rows are the dynamic rows scaled by
  // 1 / (k tau), so each row is compared with its own largest entry.
  for (int i = 0; i < n; ++i) {
    const double m = Jd.row(i).cwiseAbs().maxCoeff();
    INFO("row " << i);
    CHECK((Js.dense().row(i) - Jd.row(i)).cwiseAbs().maxCoeff() <= 1e-7 * std::max(m, 1.0));
  }
  // And the Newton matrix I - gamma J solves like the dense one.
  StructuredNewtonMatrix N;
  const double gamma = 1e-8;
  REQUIRE(N.factor(gamma, Js));
  const Eigen::MatrixXd Nd = Eigen::MatrixXd::Identity(n, n) - gamma * Jd;
  const Eigen::VectorXd b = Eigen::VectorXd::Random(n);
  Eigen::VectorXd x(n);
  N.solve(b.data(), x.data());
  const Eigen::VectorXd ref = Nd.partialPivLu().solve(b);
  // Normwise residual near round-off: Woodbury is not strictly backward stable, its
  // residual grows with the condition of the capacitance matrix, which the relaxation
  // rows (|N| ~ gamma / tau) raise: measured 7e-12 |N| |x|, bound 1e-10; and the same
  // solution as the dense LU to within eps * condition (measured 3e-11).
  CHECK((Nd * x - b).norm() <= 1e-10 * Nd.norm() * x.norm());
  CHECK((x - ref).norm() <= 1e-8 * ref.norm());
}

TEST_CASE("scene: quasi-static rule, its keys and its bad input", "[scene]") {
  const FlexibleBodySid sid = flexibleSphere2d(0.01, 12);
  auto withA = [](const std::string& lines) {
    return test::replaced(kScene, "    sid: sphere_a.sid.h5\n", "    sid: sphere_a.sid.h5\n" + lines);
  };
  // Default: 4 x the lowest elastic frequency (quasi_static_rule.h), as the explicit factor.
  Scene byDefault = buildScene(parseYamlText(kScene, "scene.yaml"), {}, fakeLoader(sid));
  Scene factor4 = buildScene(parseYamlText(withA("    quasi_static: {above_first_elastic: 4}\n"),
                                           "scene.yaml"), {}, fakeLoader(sid));
  const BodyModel& a = byDefault.system->body(0);
  const double f1 = lowestElasticFrequencyHz(a.stiffnessDiagonal());
  REQUIRE(f1 > 0.0);
  CHECK(a.quasiStatic().cutoff_hz == 4.0 * f1);
  CHECK(a.quasiStatic().index == factor4.system->body(0).quasiStatic().index);
  for (int i = 0; i < a.nq(); ++i) {
    const bool qs = std::count(a.quasiStatic().index.begin(), a.quasiStatic().index.end(), i) > 0;
    CHECK(qs == (std::sqrt(a.stiffnessDiagonal()(i)) / (2 * M_PI) >= 4.0 * f1));
  }
  Scene inHz = buildScene(parseYamlText(withA("    quasi_static: {above_hz: 1.0e99}\n"),
                                        "scene.yaml"), {}, fakeLoader(sid));
  CHECK(inHz.system->body(0).quasiStatic().empty());
  Scene off = buildScene(parseYamlText(withA("    quasi_static: false\n"), "scene.yaml"), {},
                         fakeLoader(sid));
  CHECK(off.system->body(0).quasiStatic().empty());
  CHECK(!off.system->body(1).quasiStatic().empty());  // the other body keeps the default
  // Bad input: file, line, key.
  CHECK_THAT(errorOf(withA("    quasi_static: {above_hz: 1.0e6, above_first_elastic: 4}\n"), sid),
             Catch::Contains("scene.yaml:5: key 'bodies[0].quasi_static'") &&
                 Catch::Contains("not both"));
  CHECK_THAT(errorOf(withA("    quasi_static: {above_hz: -1.0}\n"), sid),
             Catch::Contains("scene.yaml:5") && Catch::Contains("above_hz"));
  CHECK_THAT(errorOf(withA("    quasi_static: {above_first_elastic: 0.5}\n"), sid),
             Catch::Contains("scene.yaml:5") && Catch::Contains("above_first_elastic"));
  CHECK_THAT(errorOf(withA("    quasi_static: true\n"), sid),
             Catch::Contains("scene.yaml:5") && Catch::Contains("quasi_static"));
  CHECK_THAT(errorOf(withA("    quasi_static: {below_hz: 3}\n"), sid),
             Catch::Contains("scene.yaml:5") && Catch::Contains("below_hz"));
  // A velocity of a quasi-static coordinate (the last ones are the stiffest).
  std::string qdot = "    qdot: [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1.0e-3]\n";
  CHECK_THAT(errorOf(withA(qdot), sid),
             Catch::Contains("scene.yaml:5: key 'bodies[0].qdot'") &&
                 Catch::Contains("quasi-static coordinate"));
  // Warnings: damped dynamic modes below the cutoff (the test sphere's SID damps its modes
  // with zeta 0.02; scale 0 removes that).
  auto damping = [&](const std::string& a, const std::string& b) {
    return test::replaced(withA("    damping: " + a + "\n"), "    sid: sphere_b.sid.h5\n",
                   "    sid: sphere_b.sid.h5\n    damping: " + b + "\n");
  };
  Scene damped = buildScene(parseYamlText(damping("{modal_damping_ratio: 0.01}", "{scale: 0}"),
                                          "scene.yaml"), {}, fakeLoader(sid));
  REQUIRE(damped.warnings.size() == 1);
  CHECK_THAT(damped.warnings[0], Catch::Contains("body 'lower'") && Catch::Contains("damped") &&
                                     Catch::Contains("zeta up to 0.01"));
  Scene undamped = buildScene(parseYamlText(damping("{scale: 0}", "{scale: 0}"), "scene.yaml"),
                              {}, fakeLoader(sid));
  CHECK(undamped.warnings.empty());
}

// Timing of a paper-sized model (nq = 92 per body): run by hand with
//   unit_tests "[.benchmark]" -s
TEST_CASE("benchmark: flexible axisymmetric spheres, nq = 92", "[.benchmark]") {
  SimulationReport r;
  runSpheres(flexibleSphere2d(0.01, 92), 6.0e-4, 1e-6, r, "scene_test_benchmark.h5");
  WARN("max force " << r.figures.max_contact_force << " N, steps " << r.figures.solver.steps << ", rhs "
                    << r.figures.solver.rhs_evals << ", jacobians " << r.figures.solver.jacobian_evals << ", setups "
                    << r.figures.solver.linear_setups << ", wall " << r.figures.wall_time_s << " s (before "
                    << r.figures.before.wall_s << ", during " << r.figures.during.wall_s << ", after "
                    << r.figures.after.wall_s << ")");
}

TEST_CASE("scene: bad input names file, line and key", "[scene]") {
  const FlexibleBodySid sid = rigidSphere2d(0.01);
  CHECK(errorOf(kScene, sid) == "no error");
  CHECK_THAT(errorOf(test::replaced(kScene, "bodies: [lower, upper]", "bodies: [lower, uper]"), sid),
             Catch::Contains("scene.yaml:13: key 'contacts[0].bodies[1]'") &&
                 Catch::Contains("found 'uper'"));
  CHECK_THAT(errorOf(test::replaced(kScene, "penalty_factor: 1.0e13", "penalty_factor: -1.0e13"), sid),
             Catch::Contains("scene.yaml:14: key 'contacts[0].penalty_factor'"));
  CHECK_THAT(errorOf(test::replaced(kScene, "sid: sphere_b.sid.h5", "sid: nowhere.sid.h5"), sid),
             Catch::Contains("scene.yaml:8: key 'bodies[1].sid'") &&
                 Catch::Contains("SID file 'nowhere.sid.h5' not found"));
  CHECK_THAT(errorOf(test::replaced(kScene, "position: [0, 0, 0]", "position: [0.1, 0, 0]"), sid),
             Catch::Contains("key 'bodies[0].position'"));
}

TEST_CASE("scene: every scene in configs/scenes satisfies the schema", "[scene]") {
  int n = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(FFRIGA_SOURCE_DIR) + "/configs/scenes")) {
    if (entry.path().extension() != ".yaml") continue;
    INFO(entry.path());
    const JsonSchema schema(kSceneSchema, "scene.schema.json");
    REQUIRE_NOTHROW(schema.validate(loadYamlFile(entry.path().string())));
    ++n;
  }
  REQUIRE(n >= 8);
}

TEST_CASE("scene: SID names resolve against the scene folder, then each --sid-path", "[scene]") {
  const FlexibleBodySid sid = rigidSphere2d(0.01);
  std::filesystem::create_directories("sid_path_test/first");
  std::filesystem::create_directories("sid_path_test/second");
  std::ofstream("sid_path_test/second/path_a.sid.h5") << "fake";
  std::ofstream("sid_path_test/first/path_b.sid.h5") << "fake";
  // Own file names: other scene tests (maybe running in parallel) write sphere_?.sid.h5.
  const std::string text = test::replaced(test::replaced(kScene, "sphere_a", "path_a"), "sphere_b", "path_b");
  // The scene "lives" in sid_path_test/, which holds neither file itself.
  const Scene scene = buildScene(parseYamlText(text, "sid_path_test/scene.yaml"),
                                 {"sid_path_test/first", "sid_path_test/second"},
                                 [&](const std::string&, SidContent) { return sid; });
  REQUIRE(scene.sid_files[0] == "sid_path_test/second/path_a.sid.h5");
  REQUIRE(scene.sid_files[1] == "sid_path_test/first/path_b.sid.h5");
  // A file next to the scene wins over the search path.
  std::ofstream("sid_path_test/path_a.sid.h5") << "fake";
  const Scene again = buildScene(parseYamlText(text, "sid_path_test/scene.yaml"),
                                 {"sid_path_test/first", "sid_path_test/second"},
                                 [&](const std::string&, SidContent) { return sid; });
  REQUIRE(again.sid_files[0] == "sid_path_test/path_a.sid.h5");
  std::filesystem::remove_all("sid_path_test");
}

TEST_CASE("scene: the SID loader skips the visualisation mesh unless frames are asked for",
          "[scene]") {
  const FlexibleBodySid sid = rigidSphere2d(0.01);
  std::vector<SidContent> asked;
  SidLoader recording = [&](const std::string& path, SidContent content) {
    asked.push_back(content);
    return fakeLoader(sid)(path, content);
  };
  buildScene(parseYamlText(kScene, "scene.yaml"), {}, recording);
  REQUIRE(asked.size() == 2);  // sphere_a and sphere_b
  CHECK(asked[0] == SidContent::kWithoutMesh);
  asked.clear();
  const std::string framed =
      std::string(kScene) + "outputs:\n  visualisation: {interval: 1.0e-6}\n";
  // The test SID has no mesh, so the scene is refused, after the SIDs were read in full.
  CHECK_THROWS_AS(buildScene(parseYamlText(framed, "scene.yaml"), {}, recording), InputError);
  REQUIRE_FALSE(asked.empty());
  for (SidContent c : asked) CHECK(c == SidContent::kAll);
}

TEST_CASE("scene: a visualisation request on a SID without a mesh is refused", "[scene]") {
  const FlexibleBodySid sid = rigidSphere2d(0.01);  // synthetic: no visualisation mesh
  REQUIRE(sid.mesh.empty());
  const std::string text =
      std::string(kScene) + "outputs:\n  visualisation:\n    interval: 1.0e-5\n";
  const std::string e = errorOf(text, sid);
  INFO(e);
  CHECK(e.find("scene.yaml:21: key 'outputs.visualisation'") != std::string::npos);
  CHECK(e.find("has no visualisation mesh") != std::string::npos);
}
