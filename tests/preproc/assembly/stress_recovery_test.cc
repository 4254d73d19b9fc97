// Stress recovery and the visualisation mesh (issue 12): the patch test (a linear
// displacement field, a constant strain, gives the exact stress D eps at every point, also
// on the axis of an axisymmetric body), rigid translations, the mesh on the exact sphere,
// Hertz's subsurface field, SHA-256.
#include <cmath>

#include <catch2/catch.hpp>

#include "common/mechanics/hertz.h"
#include "common/base/sha256.h"
#include "common/splines/refinement.h"
#include "common/splines/spline_space.h"
#include "common/mechanics/von_mises.h"
#include "preproc/geometry/geometry_builders.h"
#include "preproc/assembly/strain_operator.h"
#include "preproc/assembly/stress_modes.h"
#include "preproc/assembly/visualisation_mesh.h"

using namespace ffriga;

namespace {

NurbsPatch refined(NurbsPatch p, int elevate, int perSpan) {
  for (int a = 0; a < p.paramDim(); ++a) {
    p = elevateDegree(p, a, elevate);
    p = insertKnots(p, a, uniformInsertionKnots(p.knots(a), perSpan));
  }
  return p;
}

IsotropicMaterial steel() {
  IsotropicMaterial m;
  m.youngs_modulus = 2.11e11;
  m.poisson_ratio = 0.3;
  return m;
}

// Points: every corner and centre of the mesh's cells (interior, boundary, axis, poles).
std::vector<ParametricPoint> samplePoints(const SplineSpace& space) {
  MeshTopology t = meshTopology(space, 2);
  return t.points;
}

}  // namespace

TEST_CASE("stress recovery: a linear field gives the exact constant stress (3D patch test)",
          "[stress]") {
  const TensorSpace space(refined(solidRod(0.002, 0.01), 1, 2));
  const int n = space.numFunctions();
  Eigen::Matrix3d G;  // displacement gradient, dimensionless
  G << 1.0e-3, 2.0e-4, -3.0e-4, 5.0e-4, -7.0e-4, 1.0e-4, -2.0e-4, 6.0e-4, 4.0e-4;
  const Eigen::Vector3d c(1e-5, -2e-5, 3e-5);
  Eigen::MatrixXd Phi(3 * n, 1);  // NURBS reproduce affine fields: u_k = G X_k + c
  for (int k = 0; k < n; ++k)
    Phi.block(3 * k, 0, 3, 1) = G * space.controlPoints().row(k).transpose() + c;
  const Eigen::Matrix3d eps = 0.5 * (G + G.transpose());
  const IsotropicMaterial m = steel();
  const Eigen::Matrix3d sigma =
      m.lambda() * eps.trace() * Eigen::Matrix3d::Identity() + 2.0 * m.mu() * eps;
  const double expect[6] = {sigma(0, 0), sigma(1, 1), sigma(2, 2),
                            sigma(0, 1), sigma(1, 2), sigma(0, 2)};
  const std::vector<ParametricPoint> pts = samplePoints(space);
  const SampledModes s = sampleModes(space, pts, Phi, m, false, Eigen::Vector3d::Zero(), 0.01);
  double err = 0.0, uerr = 0.0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    for (int r = 0; r < 6; ++r) err = std::max(err, std::abs(s.stress(6 * i + r, 0) - expect[r]));
    const Eigen::Vector3d x = s.points.row(i).transpose();
    uerr = std::max(uerr, (s.Phi.block(3 * i, 0, 3, 1) - (G * x + c)).norm());
  }
  INFO(pts.size() << " points, |sigma| = " << sigma.norm() << " Pa");
  // Rounding: sigma ~ 3e8 Pa from gradients summed over ~27 functions (1e-16 each).
  CHECK(err <= 1e-9 * sigma.norm());
  CHECK(uerr <= 1e-15);
}

TEST_CASE("stress recovery: axisymmetric patch test, also on the axis", "[stress]") {
  const TensorSpace space(refined(halfDisk(0.01), 1, 3));
  const int n = space.numFunctions();
  const double a = 4e-4, b = -7e-4, c = 2e-6;  // u_r = a r, u_y = b y + c
  Eigen::MatrixXd Phi(2 * n, 1);
  for (int k = 0; k < n; ++k) {
    Phi(2 * k, 0) = a * space.controlPoints()(k, 0);
    Phi(2 * k + 1, 0) = b * space.controlPoints()(k, 1) + c;
  }
  const IsotropicMaterial m = steel();
  // e_rr = e_tt = a, e_yy = b.
  const double tr = 2 * a + b;
  const double srr = m.lambda() * tr + 2 * m.mu() * a, syy = m.lambda() * tr + 2 * m.mu() * b;
  const std::vector<ParametricPoint> pts = samplePoints(space);
  const SampledModes s = sampleModes(space, pts, Phi, m, true, Eigen::Vector2d::Zero(), 0.01);
  double err = 0.0;
  int onAxis = 0;
  Eigen::Index worst = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double expect[6] = {srr, syy, srr, 0.0, 0.0, 0.0};
    for (int r = 0; r < 6; ++r) {
      const double e = std::abs(s.stress(6 * i + r, 0) - expect[r]);
      if (e > err) err = e, worst = static_cast<Eigen::Index>(i);
    }
    onAxis += s.points(i, 0) == 0.0;
  }
  INFO(pts.size() << " points, " << onAxis << " on the axis; worst at parameters ("
                  << s.parameters(worst, 0) << ", " << s.parameters(worst, 1) << ")");
  CHECK(onAxis >= 9);
  CHECK(err <= 1e-9 * std::abs(syy));
}

TEST_CASE("visualisation mesh: points on the exact sphere, rigid translation reproduced",
          "[stress]") {
  const double r = 0.01;
  for (const bool solid : {false, true}) {
    const TensorSpace space(solid ? refined(solidSphere(r), 0, 1) : refined(halfDisk(r), 1, 3));
    const int s = space.spaceDim(), n = space.numFunctions();
    Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(s * n, s);  // unit translations
    for (int k = 0; k < n; ++k)
      for (int c = 0; c < s; ++c) Phi(s * k + c, c) = 1.0;
    const VisualisationMesh mesh = visualisationMesh(space, solid ? 1 : 2, Phi, steel(), !solid,
                                                     Eigen::VectorXd::Zero(s), 2 * r);
    const SampledModes& S = mesh.samples;
    // Boundary: eta = 0 or 1 (the arcs of the half-disk, the two hemispheres' faces).
    double inside = 0.0, surface = 0.0, translation = 0.0, stress = 0.0;
    int onSurface = 0;
    for (Eigen::Index i = 0; i < S.points.rows(); ++i) {
      const double d = S.points.row(i).norm();
      inside = std::max(inside, d / r - 1.0);
      const double eta = S.parameters(i, 1);
      if (eta == 0.0 || eta == 1.0) {
        surface = std::max(surface, std::abs(d / r - 1.0));
        ++onSurface;
      }
      translation = std::max(
          translation,
          (S.Phi.middleRows(s * i, s) - Eigen::MatrixXd::Identity(s, s)).cwiseAbs().maxCoeff());
      // Rigid: every translation of the solid; only the axial one (u_r = const has the hoop
      // strain u_r / r) of the body of revolution.
      const int first = solid ? 0 : 1;
      stress = std::max(stress, S.stress.block(6 * i, first, 6, s - first).cwiseAbs().maxCoeff());
    }
    INFO((solid ? "sphere: " : "half-disk: ") << S.points.rows() << " points, " << onSurface
                                              << " on the surface, " << mesh.cells.rows()
                                              << " cells");
    CHECK(onSurface > 10);
    CHECK(inside <= 1e-12);
    CHECK(surface <= 1e-12);
    CHECK(translation <= 1e-14);  // partition of unity
    // A rigid translation has no strain; rounding of the gradients (1/h ~ 1e3 per metre
    // of translation) times E.
    CHECK(stress <= 1e-9 * 2.11e11 * 1e3);
    CHECK(mesh.cells.minCoeff() >= 0);
    CHECK(mesh.cells.maxCoeff() < S.points.rows());
    CHECK(mesh.cells.rows() == space.numElements() * (solid ? 1 : 4));
  }
}

TEST_CASE("Hertz: the subsurface field on the axis (Johnson eq. 3.72)", "[hertz]") {
  const double nu = 0.3, a = 1.7e-4, p0 = 2.5e9;
  const HertzAxisStress s0 = hertzAxisStress(0.0, a, p0, nu);
  CHECK(s0.sigma_z == Approx(-p0).epsilon(1e-15));
  CHECK(s0.sigma_r == Approx(-(1 + 2 * nu) / 2 * p0).epsilon(1e-15));
  const HertzAxisStress far = hertzAxisStress(1e3 * a, a, p0, nu);
  CHECK(std::abs(far.von_mises) < 1e-5 * p0);
  // The maximum: 0.62 p0 at 0.48 a (Johnson p. 62); dense sampling gives 0.6200410 at
  // 0.4808640 a.
  const HertzAxisMaximum m = hertzAxisMaximum(nu);
  CHECK(m.depth_over_a == Approx(0.4808640).epsilon(1e-6));
  CHECK(m.von_mises_over_p0 == Approx(0.6200410).epsilon(1e-7));
  // The patch: p0 = 3 F / (2 pi a^2) and F = 4/3 E* a^3 / R*.
  const HertzSphere sp{2.11e11, 0.3, 0.01, 0.0329};
  const HertzContactPatch patch = hertzContactPatch(sp, sp, 146.0);
  const double eStar = 2.11e11 / (2 * (1 - 0.09)), rStar = 0.005;
  CHECK(4.0 / 3.0 * eStar * std::pow(patch.radius, 3) / rStar == Approx(146.0).epsilon(1e-12));
  CHECK(patch.max_pressure * 2 * std::acos(-1.0) * patch.radius * patch.radius / 3 ==
        Approx(146.0).epsilon(1e-12));
}

TEST_CASE("von Mises of a uniaxial and a pure shear stress", "[stress]") {
  const double uniaxial[6] = {3.0, 0, 0, 0, 0, 0}, shear[6] = {0, 0, 0, 0, 2.0, 0};
  CHECK(vonMises(uniaxial) == Approx(3.0).epsilon(1e-15));
  CHECK(vonMises(shear) == Approx(2.0 * std::sqrt(3.0)).epsilon(1e-15));
}

TEST_CASE("SHA-256: FIPS 180-2 / NIST test vectors", "[sha256]") {
  CHECK(sha256Hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(sha256Hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  CHECK(sha256Hex(std::string(1000000, 'a')) ==
        "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST_CASE("element stiffness: the factored form equals sum B^T D B", "[stress]") {
  // Random Gauss point tables (3 points, 5 functions): isotropicStiffness against the
  // strain operator and constitutive matrix that stress recovery uses.
  const IsotropicMaterial m = steel();
  for (const bool axi : {false, true}) {
    const int s = axi ? 2 : 3, ng = 3, nb = 5;
    Eigen::MatrixXd G[3];
    for (int c = 0; c < 3; ++c) G[c] = Eigen::MatrixXd::Random(ng, nb) * 1e3;
    Eigen::MatrixXd Ke;
    isotropicStiffness(G, m, axi, Ke);
    const Eigen::MatrixXd D = constitutiveMatrix(m, axi);
    Eigen::MatrixXd reference = Eigen::MatrixXd::Zero(s * nb, s * nb), B;
    for (int g = 0; g < ng; ++g) {
      Eigen::MatrixXd grad(s, nb);
      for (int c = 0; c < s; ++c) grad.row(c) = G[c].row(g);
      // Axisymmetric: the hoop row G[2] = R / r, i.e. values G[2] at radius 1.
      const Eigen::RowVectorXd values = G[2].row(g);
      strainOperator(grad, values, axi, 1.0, false, B);
      reference += B.transpose() * D * B;
    }
    INFO((axi ? "axisymmetric" : "solid"));
    CHECK((Ke - reference).cwiseAbs().maxCoeff() <= 1e-12 * reference.cwiseAbs().maxCoeff());
  }
}
