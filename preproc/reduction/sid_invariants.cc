#include "preproc/reduction/sid_invariants.h"

#include <cmath>
#include <vector>

#include "common/base/error.h"
#include "common/splines/gauss_legendre.h"
#include "preproc/solvers/dense_products.h"
#include "preproc/assembly/elasticity_assembly.h"

namespace ffriga {

namespace {
const double kTwoPi = 2.0 * std::acos(-1.0);

Eigen::Matrix3d inertiaFromSecondMoment(const Eigen::Matrix3d& S) {
  return S.trace() * Eigen::Matrix3d::Identity() - S;
}
}  // namespace

MassProperties MassProperties::shifted(const Eigen::Vector3d& o) const {
  // int rho (x - o)(x - o)^T = S - mc o^T - o mc^T + m o o^T, J = tr(S) E - S.
  MassProperties p;
  p.mass = mass;
  p.first_moment = first_moment - mass * o;
  const Eigen::Matrix3d S0 = inertia.trace() / 2.0 * Eigen::Matrix3d::Identity() - inertia;
  const Eigen::Matrix3d S =
      S0 - first_moment * o.transpose() - o * first_moment.transpose() + mass * o * o.transpose();
  p.inertia = inertiaFromSecondMoment(S);
  return p;
}

MassProperties massProperties(const SplineSpace& space, double rho, bool axi,
                              const std::array<int, 3>& npts) {
  const int d = space.paramDim();
  const int s = space.spaceDim();
  std::array<QuadratureRule, 3> rules;
  int ng = 1;
  for (int a = 0; a < d; ++a) {
    rules[a] = gaussLegendre(npts[a]);
    ng *= npts[a];
  }
  const Eigen::MatrixXd& P = space.controlPoints();
  // Per-element sums in parallel, then added in element order (the same bits for any
  // thread count).
  struct ElementMoments {
    double m = 0.0;
    Eigen::Vector3d mc = Eigen::Vector3d::Zero();
    Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  };
  std::vector<ElementMoments> moments(space.numElements());
#pragma omp parallel
  {
    PatchBasis basis;
#pragma omp for schedule(dynamic, 16)
    for (int e = 0; e < space.numElements(); ++e) {
      double& tm = moments[e].m;
      Eigen::Vector3d& tmc = moments[e].mc;
      Eigen::Matrix3d& tS = moments[e].S;
      const ElementBox box = space.element(e);
      for (int g = 0; g < ng; ++g) {
        double xi[3] = {0, 0, 0}, w = 1.0;
        int rest = g;
        for (int a = 0; a < d; ++a) {
          const int i = rest % npts[a];
          rest /= npts[a];
          const double h = 0.5 * (box.upper[a] - box.lower[a]);
          xi[a] = box.lower[a] + h * (rules[a].points[i] + 1.0);
          w *= h * rules[a].weights[i];
        }
        space.elementBasis(e, xi, 1, basis);
        Eigen::MatrixXd Pe(basis.index.size(), s);
        for (std::size_t j = 0; j < basis.index.size(); ++j) Pe.row(j) = P.row(basis.index[j]);
        const Eigen::MatrixXd X = basis.table.topRows(1 + d) * Pe;  // value, derivatives
        Eigen::Matrix3d J = Eigen::Matrix3d::Identity();
        J.topLeftCorner(s, d) = X.bottomRows(d).transpose();
        double dm = rho * std::abs(J.determinant()) * w;
        Eigen::Vector3d x = Eigen::Vector3d::Zero();
        if (axi) {
          const double r = X(0, 0), y = X(0, 1);
          dm *= kTwoPi * r;
          x << 0.0, y, 0.0;
          tS(0, 0) += 0.5 * dm * r * r;
          tS(2, 2) += 0.5 * dm * r * r;
          tS(1, 1) += dm * y * y;
        } else {
          x = X.row(0).transpose();
          tS += dm * x * x.transpose();
        }
        tm += dm;
        tmc += dm * x;
      }
    }
  }
  double m = 0.0;
  Eigen::Vector3d mc = Eigen::Vector3d::Zero();
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  for (const ElementMoments& em : moments) {
    m += em.m;
    mc += em.mc;
    S += em.S;
  }
  MassProperties p;
  p.mass = m;
  p.first_moment = mc;
  p.inertia = inertiaFromSecondMoment(S);
  return p;
}

void computeElasticInvariants(const SparseMatrix& Ms, const Eigen::MatrixXd& X,
                              const Eigen::MatrixXd& Phi, bool axi, FlexibleBodySid* sid) {
  const int ncp = static_cast<int>(X.rows());
  const int s = static_cast<int>(X.cols());
  const int nq = static_cast<int>(Phi.cols());
  FFRIGA_CHECK(Phi.rows() == static_cast<Eigen::Index>(ncp) * s,
               "Phi has " << Phi.rows() << " rows, expected " << ncp * s);
  std::vector<Eigen::MatrixXd> Pc(s);  // Phi per component, ncp x nq
  for (int c = 0; c < s; ++c) {
    Pc[c].resize(ncp, nq);
    for (int k = 0; k < ncp; ++k) Pc[c].row(k) = Phi.row(k * s + c);
  }
  const auto full = Ms.selfadjointView<Eigen::Upper>();
  const Eigen::VectorXd m1 = full * Eigen::VectorXd::Ones(ncp);  // sum_a Ms_ab
  const Eigen::MatrixXd MX = symmetricProduct(Ms, X);            // ncp x s
  // G(d, c) as nq-vectors: G_i(d, c) = int rho x_d Phi_ic.
  std::array<std::array<Eigen::VectorXd, 3>, 3> G;
  for (auto& row : G)
    for (auto& v : row) v = Eigen::VectorXd::Zero(nq);
  sid->Ct = Eigen::MatrixXd::Zero(nq, 3);
  sid->Cr0 = Eigen::MatrixXd::Zero(nq, 3);
  sid->Cr1.assign(nq, Eigen::MatrixXd::Zero(3, nq));
  if (axi) {
    sid->Ct.col(1) = Pc[1].transpose() * m1;
    const Eigen::VectorXd a = Pc[0].transpose() * MX.col(0);
    G[0][0] = 0.5 * a;
    G[2][2] = 0.5 * a;
    G[1][1] = Pc[1].transpose() * MX.col(1);
  } else {
    for (int c = 0; c < 3; ++c) {
      sid->Ct.col(c) = Pc[c].transpose() * m1;
      for (int dd = 0; dd < 3; ++dd) G[dd][c] = Pc[c].transpose() * MX.col(dd);
    }
    sid->Cr0.col(0) = G[1][2] - G[2][1];
    sid->Cr0.col(1) = G[2][0] - G[0][2];
    sid->Cr0.col(2) = G[0][1] - G[1][0];
    // A_cd(j, i) = int rho Phi_jc Phi_id; Cr1_j(:, i) = int rho Phi_j x Phi_i.
    std::vector<Eigen::MatrixXd> MP(3);
    for (int c = 0; c < 3; ++c) MP[c] = symmetricProduct(Ms, Pc[c]);
    const Eigen::MatrixXd A01 = transposeTimes(Pc[0], MP[1]);
    const Eigen::MatrixXd A02 = transposeTimes(Pc[0], MP[2]);
    const Eigen::MatrixXd A12 = transposeTimes(Pc[1], MP[2]);
    for (int j = 0; j < nq; ++j) {
      sid->Cr1[j].row(0) = A12.row(j) - A12.col(j).transpose();
      sid->Cr1[j].row(1) = A02.col(j).transpose() - A02.row(j);
      sid->Cr1[j].row(2) = A01.row(j) - A01.col(j).transpose();
    }
  }
  sid->J1.assign(nq, Eigen::Matrix3d::Zero());
  sid->Oe = Eigen::MatrixXd::Zero(nq, 6);
  for (int i = 0; i < nq; ++i) {
    Eigen::Matrix3d Gi;
    for (int dd = 0; dd < 3; ++dd)
      for (int c = 0; c < 3; ++c) Gi(dd, c) = G[dd][c](i);
    const double tr = Gi.trace();
    sid->J1[i] = 2.0 * tr * Eigen::Matrix3d::Identity() - Gi - Gi.transpose();
    sid->Oe.row(i) << Gi(0, 0) - tr, Gi(1, 1) - tr, Gi(2, 2) - tr, Gi(0, 1) + Gi(1, 0),
        Gi(1, 2) + Gi(2, 1), Gi(0, 2) + Gi(2, 0);
  }
}

}  // namespace ffriga
