#include "preproc/assembly/stress_modes.h"

#include <algorithm>
#include <cmath>

#include "common/base/error.h"

namespace ffriga {

namespace {

// The map is singular at a point where |det J| < kSingular |det J(element centre)|; the
// derivatives are then taken kInside of the element's span inside it.
constexpr double kSingular = 1e-6;
constexpr double kInside = 0.05;

struct PointWork {
  PatchBasis basis;
  Eigen::MatrixXd grad, B, PhiLoc;
};

// Jacobian dx/dxi (s x d) and position from a basis table.
void geometryAt(const SplineSpace& space, const PatchBasis& R, Eigen::VectorXd& x,
                Eigen::MatrixXd& J) {
  const Eigen::MatrixXd& P = space.controlPoints();
  const int s = space.spaceDim(), d = space.paramDim();
  x.setZero(s);
  J.setZero(s, d);
  for (std::size_t j = 0; j < R.index.size(); ++j) {
    const int k = R.index[j];
    for (int c = 0; c < s; ++c) {
      x(c) += R.table(0, j) * P(k, c);
      for (int a = 0; a < d; ++a) J(c, a) += R.table(1 + a, j) * P(k, c);
    }
  }
}

// Where the derivatives of point pt are taken: the basis table (in w) and Jacobian J (on
// entry the point's) at the point, or kInside of the element's span towards its centre if
// the map is singular at the point (`radius` then becomes x_0 there); false if singular
// there too.
bool derivativePoint(const SplineSpace& space, const ParametricPoint& pt, PointWork& w,
                     Eigen::VectorXd& xd, Eigen::MatrixXd& J, Eigen::MatrixXd& Jc, double& radius) {
  const int d = space.paramDim();
  const ElementBox box = space.element(pt.element);
  double centre[3] = {0, 0, 0};
  for (int a = 0; a < d; ++a) centre[a] = 0.5 * (box.lower[a] + box.upper[a]);
  space.elementBasis(pt.element, centre, 1, w.basis);
  geometryAt(space, w.basis, xd, Jc);
  const double detCentre = std::abs(Jc.determinant());
  if (!(std::abs(J.determinant()) >= kSingular * detCentre)) {
    double xi[3] = {pt.xi[0], pt.xi[1], pt.xi[2]};
    for (int a = 0; a < d; ++a) xi[a] += kInside * (centre[a] - xi[a]) / 0.5;
    space.elementBasis(pt.element, xi, 1, w.basis);
    geometryAt(space, w.basis, xd, J);
    radius = xd(0);
    if (!(std::abs(J.determinant()) >= kSingular * detCentre)) return false;
  } else {
    space.elementBasis(pt.element, pt.xi.data(), 1, w.basis);
  }
  return true;
}

// The stress modes S = D B Phi_loc of one point (6 x nq; axisymmetric: rows rr, yy, tt, ry,
// the rest zero) from the basis table in w and the Jacobian J of the same point.
void stressAt(const Eigen::MatrixXd& J, const Eigen::MatrixXd& Phi, const Eigen::MatrixXd& D,
              bool axisymmetric, double radius, double size, int s, PointWork& w,
              Eigen::Block<Eigen::MatrixXd> S) {
  const int d = static_cast<int>(J.cols());
  const int nq = static_cast<int>(Phi.cols());
  const int nb = static_cast<int>(w.basis.index.size());
  const Eigen::MatrixXd Jinv = J.inverse();  // d = s
  w.grad.resize(s, nb);
  for (int c = 0; c < s; ++c)
    for (int j = 0; j < nb; ++j) {
      double v = 0.0;
      for (int a = 0; a < d; ++a) v += Jinv(a, c) * w.basis.table(1 + a, j);
      w.grad(c, j) = v;
    }
  const bool onAxis = axisymmetric && std::abs(radius) <= 1e-12 * size;
  strainOperator(w.grad, w.basis.table.row(0), axisymmetric, radius, onAxis, w.B);
  w.PhiLoc.resize(static_cast<Eigen::Index>(nb) * s, nq);
  for (int j = 0; j < nb; ++j)
    w.PhiLoc.middleRows(static_cast<Eigen::Index>(j) * s, s) =
        Phi.middleRows(static_cast<Eigen::Index>(w.basis.index[j]) * s, s);
  const Eigen::MatrixXd sigma = D * (w.B * w.PhiLoc);  // ns x nq
  if (!axisymmetric) {
    S = sigma;
  } else {
    const int ns = strainComponents(axisymmetric);
    for (int r = 0; r < ns; ++r) S.row(r) = sigma.row(r);  // rr, yy, tt, ry; yz = xz = 0
  }
}

}  // namespace

SampledModes sampleModes(const SplineSpace& space, const std::vector<ParametricPoint>& points,
                         const Eigen::MatrixXd& Phi, const IsotropicMaterial& material,
                         bool axisymmetric, const Eigen::VectorXd& origin, double size) {
  const int s = space.spaceDim(), d = space.paramDim();
  const int np = static_cast<int>(points.size());
  const int nq = static_cast<int>(Phi.cols());
  FFRIGA_CHECK(Phi.rows() == static_cast<Eigen::Index>(space.numFunctions()) * s,
               "Phi has " << Phi.rows() << " rows for " << space.numFunctions()
                          << " control points");
  const Eigen::MatrixXd D = constitutiveMatrix(material, axisymmetric);
  SampledModes out;
  out.points.resize(np, s);
  out.parameters.resize(np, d);
  out.Phi.setZero(static_cast<Eigen::Index>(np) * s, nq);
  out.stress.setZero(static_cast<Eigen::Index>(np) * 6, nq);
  bool singular = false;
#pragma omp parallel
  {
    PointWork w;
    Eigen::VectorXd x, xd;
    Eigen::MatrixXd J, Jc;
#pragma omp for schedule(static)
    for (int i = 0; i < np; ++i) {
      const ParametricPoint& pt = points[i];
      space.elementBasis(pt.element, pt.xi.data(), 1, w.basis);
      geometryAt(space, w.basis, x, J);
      for (int a = 0; a < d; ++a) out.parameters(i, a) = pt.xi[a];
      out.points.row(i) = (x - origin.head(s)).transpose();
      const int nb = static_cast<int>(w.basis.index.size());
      // Displacement modes: sum_k R_k Phi_k.
      for (int j = 0; j < nb; ++j) {
        const int k = w.basis.index[j];
        out.Phi.middleRows(static_cast<Eigen::Index>(i) * s, s) +=
            w.basis.table(0, j) * Phi.middleRows(static_cast<Eigen::Index>(k) * s, s);
      }
      double radius = x(0);  // of the point where the derivatives are taken
      if (!derivativePoint(space, pt, w, xd, J, Jc, radius)) {
#pragma omp atomic write
        singular = true;
        continue;
      }
      stressAt(J, Phi, D, axisymmetric, radius, size, s, w,
               out.stress.middleRows(static_cast<Eigen::Index>(i) * 6, 6));
    }
  }
  if (singular) {
    throw ComputeError("stress modes: the geometry map is singular at a sample point and "
                       "inside its element");
  }
  return out;
}

}  // namespace ffriga
