

// Eigen solver and reduction: eigenpair residuals and mass normalisation, the rigid-body
// modes of a free body, convergence to Lamb's breathing frequency of a free sphere, and a
// Craig-Bampton model that reproduces the lowest free-free frequencies (paper Eq. 13).
#include "preproc/reduction/craig_bampton.h"

#include <cmath>

#include <catch2/catch.hpp>

#include "common/splines/refinement.h"
#include "preproc/assembly/rigid_body_modes.h"
#include "preproc/geometry/contact_region.h"
#include "preproc/geometry/geometry_builders.h"
#include "preproc/reduction/characteristic_constraint_modes.h"
#include "preproc/reduction/marker_points.h"
#include "preproc/solvers/eigen_solver.h"

using namespace ffriga;

namespace {

const double kE = 2.11e11, kNu = 0.3, kRho = 7850, kRadius = 0.01;

struct Model {
  std::unique_ptr<TensorSpace> space;
  std::unique_ptr<DofMap> dofs;
  ElasticSystem sys;
  bool axi = true;
};

Model sphereModel(bool axi, int elevate, int insert) {
  NurbsPatch patch = axi ? halfDisk(kRadius) : solidSphere(kRadius);
  for (int a = 0; a < patch.paramDim(); ++a) patch = elevateDegree(patch, a, elevate);
  for (int a = 0; a < patch.paramDim(); ++a)
    patch = insertKnots(patch, a, uniformInsertionKnots(patch.knots(a), insert));
  Model m;
  m.axi = axi;
  m.space = std::make_unique<TensorSpace>(patch);
  m.dofs = std::make_unique<DofMap>(*m.space, axi);
  ElasticityModel em{axi, kE, kNu, kRho, {}};
  for (int a = 0; a < patch.paramDim(); ++a) em.gauss_points[a] = patch.degree(a) + 1;
  m.sys = assembleElasticity(*m.space, *m.dofs, em);
  return m;
}

// Lamb (1882), radial (breathing) mode of a free elastic sphere: with x = omega a / c_p,
//   1 - x cot x = x^2 (lambda + 2 mu) / (4 mu)    (e.g. Eringen & Suhubi, Elastodynamics
// vol. 2, Sect. 8.13). Returns omega of the lowest root, by bisection.
double lambBreathingOmega() {
  const double lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu)), mu = kE / (2 * (1 + kNu));
  auto f = [&](double x) { return 1.0 - x / std::tan(x) - x * x * (lambda + 2 * mu) / (4 * mu); };
  double a = 1.0, b = 3.14159;  // f(1) > 0, f -> -inf as x -> pi
  for (int i = 0; i < 200; ++i) {
    const double c = 0.5 * (a + b);
    (f(a) * f(c) <= 0 ? b : a) = c;
  }
  return 0.5 * (a + b) * std::sqrt((lambda + 2 * mu) / kRho) / kRadius;
}

void checkEigenpairs(const Model& m, const EigenResult& r) {
  for (int j = 0; j < r.values.size(); ++j) {
    const Eigen::VectorXd phi = r.vectors.col(j);
    const Eigen::VectorXd Kphi = symmetricProduct(m.sys.K, phi);
    const Eigen::VectorXd Mphi = symmetricProduct(m.sys.M, phi);
    // Rigid modes have K phi ~ 0: measure them against the stiffness scale instead.
    const double scale = std::max(Kphi.norm(), 1e-6 * m.sys.K.diagonal().maxCoeff() * phi.norm());
    INFO("mode " << j << " lambda " << r.values(j));
    CHECK((Kphi - r.values(j) * Mphi).norm() <= 1e-8 * scale);
    CHECK(std::abs(phi.dot(Mphi) - 1.0) < 1e-12);  // normalisation, round-off of one dot product
  }
}

int countRigid(const Eigen::VectorXd& values) {
  // Rigid eigenvalues are round-off (~1e-16 of the largest stiffness); elastic ones of this
  // sphere are > 1e11 (rad/s)^2.
  int n = 0;
  for (int j = 0; j < values.size(); ++j) n += std::abs(values(j)) < 1e-6 * values.maxCoeff();
  return n;
}

}  // namespace

TEST_CASE("free-free axisymmetric sphere: one rigid mode, residuals, normalisation", "[eigen]") {
  const Model m = sphereModel(true, 2, 3);
  EigenOptions o;
  o.count = 8;
  o.shift = -1e10;  // below the rigid modes, ~1 % of the first elastic eigenvalue
  const EigenResult r = solveEigenproblem(m.sys.K, m.sys.M, o);
  CHECK(countRigid(r.values) == 1);
  checkEigenpairs(m, r);
}

TEST_CASE("free-free 3D sphere: six rigid modes, residuals, normalisation", "[eigen]") {
  const Model m = sphereModel(false, 1, 1);
  EigenOptions o;
  o.count = 10;
  o.shift = -1e10;  // below the rigid modes, ~1 % of the first elastic eigenvalue
  const EigenResult r = solveEigenproblem(m.sys.K, m.sys.M, o);
  CHECK(countRigid(r.values) == 6);
  checkEigenpairs(m, r);
}

TEST_CASE("breathing frequency converges to Lamb's solution", "[eigen]") {
  const double exact = lambBreathingOmega();
  double previous = 1.0;
  for (int insert : {1, 3, 7}) {
    const Model m = sphereModel(true, 2, insert);
    EigenOptions o;
    o.count = 16;
    o.shift = -1e10;  // below the rigid modes, ~1 % of the first elastic eigenvalue
    const EigenResult r = solveEigenproblem(m.sys.K, m.sys.M, o);
    double err = 1.0;
    for (int j = 0; j < r.values.size(); ++j)
      err = std::min(err, std::abs(std::sqrt(std::max(r.values(j), 0.0)) - exact) / exact);
    INFO("insert " << insert << " exact " << exact / (2 * M_PI) << " Hz, error " << err);
    CHECK(err < previous);
    previous = err;
  }
  // 8 x 8 elements of degree (4, 3): the error is at the 1e-6 level.
  CHECK(previous < 1e-5);
}

namespace {

// The options of a Craig-Bampton reduction of m with the interface of region.
ReductionOptions regionOptions(const Model& m, const ContactRegion& region, int normal_modes) {
  ReductionOptions o;
  o.normal_modes = normal_modes;
  o.rigid_modes = rigidBodyModes(*m.space, *m.dofs, m.axi);
  o.interface.assign(m.dofs->numDofs(), false);
  for (int k : interfaceControlPoints(*m.space, region))
    for (int c = 0; c < m.dofs->components(); ++c)
      if (m.dofs->dof(k, c) >= 0) o.interface[m.dofs->dof(k, c)] = true;
  return o;
}

// Phi^T M Phi = E, Phi^T K Phi = diag(omega^2) (Eq. 13) and no rigid content (Buckens:
// R^T M Phi = 0, i.e. int rho u dV = 0 etc.), to round-off of sums over all DOFs.
void checkOrthonormalModes(const Model& m, const ReductionOptions& o, const ReducedModel& red) {
  const int nq = static_cast<int>(red.Phi.cols());
  const Eigen::MatrixXd Me = red.Phi.transpose() * symmetricProduct(m.sys.M, red.Phi);
  const Eigen::MatrixXd Ke = red.Phi.transpose() * symmetricProduct(m.sys.K, red.Phi);
  CHECK((Me - Eigen::MatrixXd::Identity(nq, nq)).cwiseAbs().maxCoeff() < 1e-10);
  const Eigen::MatrixXd off = Ke - Eigen::MatrixXd(red.omega2.asDiagonal());
  CHECK(off.cwiseAbs().maxCoeff() < 1e-10 * red.omega2.maxCoeff());
  const Eigen::MatrixXd RMPhi = o.rigid_modes.transpose() * symmetricProduct(m.sys.M, red.Phi);
  CHECK(RMPhi.cwiseAbs().maxCoeff() < 1e-10 * std::sqrt(o.rigid_modes.squaredNorm()));
}

}  // namespace

TEST_CASE("Craig-Bampton reproduces the lowest free-free frequencies", "[reduction]") {
  for (bool axi : {true, false}) {
    const Model m = axi ? sphereModel(true, 2, 7) : sphereModel(false, 1, 2);
    ContactRegion region;
    region.direction = 1;
    region.upper = true;
    if (axi) {
      region.bounds = {{0.0, 0.25}};
    } else {
      region.bounds = {{0.25, 0.75}, {0.0, 0.25}};
    }
    REQUIRE(!interfaceControlPoints(*m.space, region).empty());
    // The paper uses 10 (2D) and 50 (3D) normal modes. A free body whose interface is a
    // small surface patch needs more fixed-interface modes for its lowest free-free modes:
    // measured errors of the lowest mode 0.18 % / 0.06 % / 0.03 % with 10 / 20 / 30 modes (2D).
    const ReductionOptions o = regionOptions(m, region, axi ? 20 : 60);
    const ReducedModel red = reduceBody(m.sys.K, m.sys.M, o);
    CHECK(red.rigid_dropped == (axi ? 1 : 6));
    checkOrthonormalModes(m, o, red);
    // Free-free reference.
    EigenOptions eo;
    eo.count = 6 + (axi ? 1 : 6);
    eo.shift = -1e10;  // below the rigid modes, ~1 % of the first elastic eigenvalue
    const EigenResult ff = solveEigenproblem(m.sys.K, m.sys.M, eo);
    const int nr = axi ? 1 : 6;
    for (int j = 0; j < 5; ++j) {
      const double f = std::sqrt(ff.values(nr + j)), fr = std::sqrt(red.omega2(j));
      INFO("axi " << axi << " mode " << j << " free-free " << f << " CB " << fr);
      // CB frequencies are Rayleigh-Ritz upper bounds (up to round-off). The lowest ones
      // (2D: two modes; 3D: the lowest of the n = 2 quintuplet) within 0.1 % (issue 4); the
      // next within 0.2 % (measured 0.02-0.19 %).
      CHECK(fr >= f * (1 - 1e-9));
      CHECK(fr <= f * (j < (axi ? 2 : 1) ? 1.001 : 1.002));
    }
  }
}

TEST_CASE("modal reduction keeps the free-free frequencies; tangent frame", "[reduction]") {
  const Model m = sphereModel(false, 1, 1);
  ReductionOptions o;
  o.method = ReductionMethod::kModal;
  o.normal_modes = 8;
  o.rigid_modes = rigidBodyModes(*m.space, *m.dofs, false);
  const ReducedModel red = reduceBody(m.sys.K, m.sys.M, o);
  CHECK(red.rigid_dropped == 6);
  REQUIRE(red.omega2.size() == 8);
  // Buckens projection of exact free-free modes changes nothing but round-off.
  for (int j = 0; j < 8; ++j)
    CHECK(red.omega2(j) == Approx(red.normal_mode_omega2(j)).epsilon(1e-9));
  // Tangent frame at the centre: every mode has zero displacement and rotation there.
  o.method = ReductionMethod::kCraigBampton;
  o.frame = FrameKind::kTangent;
  o.normal_modes = 6;
  ContactRegion region{1, true, {{0.25, 0.75}, {0.0, 0.25}}};
  o.interface.assign(m.dofs->numDofs(), false);
  for (int k : interfaceControlPoints(*m.space, region))
    for (int c = 0; c < 3; ++c) o.interface[m.dofs->dof(k, c)] = true;
  const std::vector<double> xi = {0.5, 0.5, 0.3};  // an interior, regular point
  o.frame_conditions = tangentFrameConditions(*m.space, *m.dofs, xi, false);
  const ReducedModel tan = reduceBody(m.sys.K, m.sys.M, o);
  CHECK(tan.rigid_dropped == 6);
  const Eigen::MatrixXd CPhi = o.frame_conditions * tan.Phi;
  CHECK(CPhi.cwiseAbs().maxCoeff() < 1e-10 * tan.Phi.cwiseAbs().maxCoeff());
  const int nq = static_cast<int>(tan.Phi.cols());
  const Eigen::MatrixXd Me = tan.Phi.transpose() * symmetricProduct(m.sys.M, tan.Phi);
  CHECK((Me - Eigen::MatrixXd::Identity(nq, nq)).cwiseAbs().maxCoeff() < 1e-10);
}


// Characteristic constraint modes (characteristic_constraint_modes.h) span a subspace of the
// full Craig-Bampton basis: all of them reproduce it, fewer give Rayleigh-Ritz upper bounds
// of its frequencies, and the subspaces of growing counts are nested (frequencies fall).
TEST_CASE("characteristic constraint modes: all reproduce the full interface, fewer bound it",
          "[reduction]") {
  for (bool axi : {true, false}) {
    const Model m = axi ? sphereModel(true, 2, 7) : sphereModel(false, 1, 2);
    const ContactRegion region = axi ? ContactRegion{1, true, {{0.0, 0.25}}}
                                     : ContactRegion{1, true, {{0.25, 0.75}, {0.0, 0.25}}};
    const int nm = axi ? 10 : 20, nr = axi ? 1 : 6;
    ReductionOptions o = regionOptions(m, region, nm);
    const ReducedModel full = reduceBody(m.sys.K, m.sys.M, o);
    const int nb = full.interface_dofs;
    REQUIRE(nb > (axi ? 10 : 30));
    INFO("axi " << axi << ", " << nb << " interface DOFs");
    o.interface_modes = nb;  // more than the region has elastic ones: all are kept
    const ReducedModel all = reduceBody(m.sys.K, m.sys.M, o);
    CHECK(all.characteristic_rigid == nr);
    CHECK(all.characteristic_elastic == nb - nr);
    REQUIRE(all.omega2.size() == full.omega2.size());
    for (int j = 0; j < full.omega2.size(); ++j)  // the same space: round-off of the solves
      CHECK(all.omega2(j) == Approx(full.omega2(j)).epsilon(1e-8));
    Eigen::VectorXd previous = all.omega2;
    for (int count : axi ? std::vector<int>{6, 3, 1} : std::vector<int>{24, 12, 4}) {
      o.interface_modes = count;
      const ReducedModel red = reduceBody(m.sys.K, m.sys.M, o);
      INFO(count << " elastic characteristic modes asked for, " << red.characteristic_elastic
                 << " kept");
      // A cluster of equal frequencies is kept whole (the 3D region is symmetric).
      CHECK(red.characteristic_elastic >= count);
      CHECK(red.characteristic_elastic < count + 4);
      CHECK(red.rigid_dropped == nr);
      CHECK(red.omega2.size() == nm + red.characteristic_elastic);
      CHECK(red.constraint_modes == nr + red.characteristic_elastic);
      checkOrthonormalModes(m, o, red);
      for (int j = 0; j < red.omega2.size(); ++j) {
        CHECK(red.omega2(j) >= full.omega2(j) * (1 - 1e-9));
        CHECK(red.omega2(j) >= previous(j) * (1 - 1e-9));
      }
      previous = red.omega2;
    }
  }
}

// Interface DOFs of a marker keep their physical constraint modes: the transformation is the
// identity on them, the characteristic modes vanish there, and every rigid motion of the
// interface stays in the reduced space (so the frame projection drops exactly nr directions).
TEST_CASE("characteristic constraint modes keep retained interface DOFs exact", "[reduction]") {
  const Model m = sphereModel(false, 1, 2);
  const ContactRegion region{1, true, {{0.25, 0.75}, {0.0, 0.25}}};
  ReductionOptions o = regionOptions(m, region, 10);
  const ReducedModel full = reduceBody(m.sys.K, m.sys.M, o);
  // Retain the DOFs of the first three interface control points (a "marker").
  o.interface_retained.assign(m.dofs->numDofs(), false);
  std::vector<bool> retained;
  for (int j = 0, seen = 0; j < m.dofs->numDofs(); ++j) {
    if (!o.interface[j]) continue;
    retained.push_back(seen++ < 9);
    o.interface_retained[j] = retained.back();
  }
  o.interface_modes = 8;
  const ReducedModel red = reduceBody(m.sys.K, m.sys.M, o);
  CHECK(red.rigid_dropped == 6);
  CHECK(red.constraint_modes == red.characteristic_rigid + red.characteristic_elastic + 9);
  checkOrthonormalModes(m, o, red);
  for (int j = 0; j < red.omega2.size(); ++j) CHECK(red.omega2(j) >= full.omega2(j) * (1 - 1e-9));
  // The transformation itself, on the Craig-Bampton reduced matrices of a small problem:
  // random SPD interface blocks with a null space of two "rigid" motions.
  const int nm = 2, nb = static_cast<int>(retained.size());
  Eigen::MatrixXd N = Eigen::MatrixXd::Random(nb, 2);  // the rigid interface motions
  Eigen::MatrixXd B = Eigen::MatrixXd::Random(nb, nb);
  const Eigen::MatrixXd P =
      Eigen::MatrixXd::Identity(nb, nb) - N * (N.transpose() * N).ldlt().solve(N.transpose());
  Eigen::MatrixXd Kr = Eigen::MatrixXd::Zero(nm + nb, nm + nb), Mr = Kr;
  Kr.topLeftCorner(nm, nm) = Eigen::Vector2d(1.0, 2.0).asDiagonal();
  Kr.bottomRightCorner(nb, nb) = P * (B * B.transpose()) * P;  // K_c N = 0
  const Eigen::MatrixXd C = Eigen::MatrixXd::Random(nm + nb, nm + nb);
  Mr = C * C.transpose() + (nm + nb) * Eigen::MatrixXd::Identity(nm + nb, nm + nb);
  const InterfaceReduction ir = characteristicConstraintModes(Mr, Kr, nm, retained, 5);
  REQUIRE(ir.retained == 9);
  // Nine fixed DOFs leave the two null directions no room in the region block (K_cc is
  // positive definite): no zero modes, so the rigid motions must come from the static part.
  REQUIRE(ir.rigid == 0);
  const int cols = static_cast<int>(ir.T.cols());
  CHECK(cols == nm + ir.elastic + 9);
  for (int k = 0, m_ = 0; k < nb; ++k) {
    if (!retained[k]) continue;
    for (int j = 0; j < cols; ++j) CHECK(ir.T(nm + k, j) == (j == cols - 9 + m_ ? 1.0 : 0.0));
    ++m_;
  }
  // Each rigid motion is T z for some z (least squares residual at round-off).
  const Eigen::MatrixXd Tb = ir.T.bottomRows(nb);
  for (int r = 0; r < 2; ++r) {
    const Eigen::VectorXd z = Tb.colPivHouseholderQr().solve(N.col(r));
    CHECK((Tb * z - N.col(r)).norm() < 1e-9 * N.col(r).norm());
  }
}
