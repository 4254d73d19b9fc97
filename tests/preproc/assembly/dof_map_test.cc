// Degrees of freedom (preproc/assembly/dof_map.h) and rigid-body modes
// (preproc/assembly/rigid_body_modes.h), directly, on the paper's degenerate patches: tied
// coincident control points share their DOFs, the axis condition of the half-disk fixes u_r,
// the numbering increases with (node, component), restrict is the inverse of expand, and the
// rigid modes are exact displacement fields t + w x x of the NURBS geometry.
#include "preproc/assembly/dof_map.h"

#include <cmath>
#include <random>
#include <set>

#include <catch2/catch.hpp>

#include "common/splines/refinement.h"
#include "preproc/assembly/rigid_body_modes.h"
#include "preproc/geometry/geometry_builders.h"

using namespace ffriga;

namespace {

NurbsPatch refined(NurbsPatch patch, int insert) {
  for (int a = 0; a < patch.paramDim(); ++a)
    patch = insertKnots(patch, a, uniformInsertionKnots(patch.knots(a), insert));
  return patch;
}

// The numbering rules of the header for any map: every control point has the DOFs of its
// node (the smallest index of its group), DOFs 0 .. numDofs-1 are used once each, in order
// of (node, component), and fixed components are -1.
void checkNumbering(const DofMap& dofs) {
  int next = 0;
  for (int k = 0; k < dofs.numControlPoints(); ++k) {
    REQUIRE(dofs.node(k) <= k);
    for (int c = 0; c < dofs.components(); ++c) {
      REQUIRE(dofs.dof(k, c) == dofs.dof(dofs.node(k), c));
      if (dofs.node(k) != k || dofs.dof(k, c) < 0) continue;
      REQUIRE(dofs.dof(k, c) == next++);
    }
  }
  REQUIRE(next == dofs.numDofs());
}

}  // namespace

TEST_CASE("DOF map of the solid sphere: coincident points tied, numbering and restriction",
          "[dofs]") {
  // solidSphere's axis, equator and seam collapse rows of control points.
  const TensorSpace space(refined(solidSphere(0.01), 1));
  const Eigen::MatrixXd& P = space.controlPoints();
  const int ncp = static_cast<int>(P.rows());
  const DofMap dofs(space, false);
  checkNumbering(dofs);
  CHECK(dofs.components() == 3);
  CHECK(dofs.numFixedDofs() == 0);  // no axis condition in 3D
  CHECK(dofs.numTiedPoints() > 0);
  CHECK(dofs.numDofs() == 3 * (ncp - dofs.numTiedPoints()));
  // Tied exactly where the control points coincide: the default tolerance is 1e-12 of the
  // net's size (2e-14 m here); distinct points of this net are > 1e-4 m apart.
  std::set<int> nodes;
  for (int k = 0; k < ncp; ++k) {
    nodes.insert(dofs.node(k));
    CHECK((P.row(k) - P.row(dofs.node(k))).norm() <= DofMap::defaultTolerance(space));
  }
  for (int k : nodes)
    for (int l : nodes)
      if (k < l) REQUIRE((P.row(k) - P.row(l)).norm() > 1e-6);
  CHECK(static_cast<int>(nodes.size()) == ncp - dofs.numTiedPoints());
  // restrict(expand(x)) = x for any DOF vector; expand gives tied points equal rows.
  std::mt19937 gen(31);
  auto uniform = [&gen](double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(gen);
  };
  Eigen::MatrixXd x(dofs.numDofs(), 2);
  for (int i = 0; i < x.size(); ++i) x(i) = uniform(-1, 1);
  const Eigen::MatrixXd u = dofs.expand(x);
  REQUIRE(u.rows() == 3 * ncp);
  CHECK(dofs.restrict(u) == x);
  for (int k = 0; k < ncp; ++k) CHECK(u.middleRows(3 * k, 3) == u.middleRows(3 * dofs.node(k), 3));
  // Explicit groups: only those are tied.
  const DofMap two(space, false, {{0, 5}, {7, 9, 11}});
  checkNumbering(two);
  CHECK(two.numTiedPoints() == 3);
  CHECK(two.node(5) == 0);
  CHECK(two.node(11) == 7);
  for (int k = 0; k < ncp; ++k)
    if (k != 5 && k != 9 && k != 11) CHECK(two.node(k) == k);
  CHECK(two.numDofs() == 3 * (ncp - 3));
}

TEST_CASE("DOF map of the half-disk: u_r fixed on the axis, the collapsed edge tied", "[dofs]") {
  const TensorSpace space(refined(halfDisk(0.01), 2));
  const Eigen::MatrixXd& P = space.controlPoints();
  const int ncp = static_cast<int>(P.rows());
  const DofMap dofs(space, true);
  checkNumbering(dofs);
  CHECK(dofs.components() == 2);
  CHECK(dofs.numTiedPoints() > 0);  // the edge xi = 1 collapsed into (r, 0)
  int onAxis = 0;
  for (int k = 0; k < ncp; ++k) {
    const bool axis = std::abs(P(k, 0)) <= DofMap::defaultTolerance(space);
    if (axis && dofs.node(k) == k) ++onAxis;
    CHECK((dofs.dof(k, 0) < 0) == axis);  // u_r = 0 exactly on the axis, free elsewhere
    CHECK(dofs.dof(k, 1) >= 0);           // u_y always free
  }
  CHECK(onAxis > 2);  // the axis edge has a row of control points
  CHECK(dofs.numFixedDofs() == onAxis);
  CHECK(dofs.numDofs() == 2 * (ncp - dofs.numTiedPoints()) - onAxis);
  // Fixed components expand to zero.
  const Eigen::MatrixXd u = dofs.expand(Eigen::MatrixXd::Ones(dofs.numDofs(), 1));
  for (int k = 0; k < ncp; ++k) CHECK(u(2 * k) == (dofs.dof(k, 0) < 0 ? 0.0 : 1.0));
  // The axisymmetric rigid mode: translation along the axis y.
  const Eigen::MatrixXd U = dofs.expand(rigidBodyModes(space, dofs, true));
  REQUIRE(U.cols() == 1);
  for (int k = 0; k < ncp; ++k) {
    CHECK(U(2 * k) == 0.0);
    CHECK(U(2 * k + 1) == 1.0);
  }
}

TEST_CASE("rigid-body modes are the exact fields t + w x x of the NURBS geometry", "[dofs]") {
  // u(xi) = sum_k R_k(xi) u_k with u_k = t + w x X_k equals t + w x x(xi) because the
  // rational basis is a partition of unity and x(xi) = sum_k R_k X_k: at random parameters of
  // every element, to round-off of sums of ~30 terms of size 1 (t, w) x 0.01 m.
  const TensorSpace space(refined(solidSphere(0.01), 1));
  const DofMap dofs(space, false);
  const Eigen::MatrixXd U = dofs.expand(rigidBodyModes(space, dofs, false));
  REQUIRE(U.cols() == 6);
  const Eigen::MatrixXd& P = space.controlPoints();
  std::mt19937 gen(32);
  auto uniform = [&gen](double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(gen);
  };
  double worst = 0.0;
  for (int e = 0; e < space.numElements(); ++e) {
    const ElementBox box = space.element(e);
    double xi[3];
    for (int a = 0; a < 3; ++a) xi[a] = uniform(box.lower[a], box.upper[a]);
    PatchBasis basis;
    space.elementBasis(e, xi, 0, basis);
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    Eigen::Matrix<double, 3, 6> u = Eigen::Matrix<double, 3, 6>::Zero();
    for (std::size_t i = 0; i < basis.index.size(); ++i) {
      const int k = basis.index[i];
      x += basis.table(0, i) * P.row(k).transpose();
      u += basis.table(0, i) * U.middleRows(3 * k, 3);
    }
    Eigen::Matrix<double, 3, 6> expected;
    expected.leftCols<3>().setIdentity();
    for (int c = 0; c < 3; ++c) expected.col(3 + c) = Eigen::Vector3d::Unit(c).cross(x);
    worst = std::max(worst, (u - expected).cwiseAbs().maxCoeff());
  }
  INFO("largest deviation " << worst);
  CHECK(worst < 1e-14);
  // The six modes are independent (a rank-deficient set would leave a rigid motion free).
  CHECK(Eigen::FullPivLU<Eigen::MatrixXd>(U).rank() == 6);
}
