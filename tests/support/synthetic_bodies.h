// Test fixtures: consistent synthetic SIDs (common/sid/sid.h) whose invariants are sums over
// point masses, so that every term of Eq. (1) is exact for the discrete model:
//   m = sum m_a, m c = sum m_a x_a, J0 = sum m_a (x_a.x_a E - x_a x_a^T),
//   Ct^T = sum m_a Phi_a, Cr0^T = sum m_a x_a~ Phi_a, Cr1_j(:, i) = sum m_a Phi_aj~ Phi_ai,
//   J1_j = -sum m_a (x_a~ Phi_aj~ + Phi_aj~ x_a~), Me = Phi^T M Phi, Ke = Phi^T K Phi.
#pragma once

#include <Eigen/Dense>

#include "common/sid/sid.h"
#include "runtime/bodies/rotation.h"

namespace ffriga::test {

// Fills the inertia invariants of `sid` from point masses m (N) at rows of X (N x 3) with
// modes Phi (3N x nq); sets Me, Ke from M, K.
inline void pointMassInvariants(FlexibleBodySid& sid, const Eigen::VectorXd& m,
                                const Eigen::MatrixXd& X, const Eigen::MatrixXd& Phi,
                                const Eigen::MatrixXd& K) {
  const int N = static_cast<int>(m.size()), nq = static_cast<int>(Phi.cols());
  sid.model = ffriga::ModelKind::kSolid;
  sid.space_dim = 3;
  sid.mass = m.sum();
  sid.first_moment.setZero();
  sid.inertia.setZero();
  sid.Ct = Eigen::MatrixXd::Zero(nq, 3);
  sid.Cr0 = Eigen::MatrixXd::Zero(nq, 3);
  sid.Cr1.assign(nq, Eigen::MatrixXd::Zero(3, nq));
  sid.J1.assign(nq, Eigen::Matrix3d::Zero());
  for (int a = 0; a < N; ++a) {
    const Eigen::Vector3d x = X.row(a).transpose();
    const Eigen::MatrixXd Pa = Phi.middleRows(3 * a, 3);
    sid.first_moment += m(a) * x;
    sid.inertia += m(a) * (x.squaredNorm() * Eigen::Matrix3d::Identity() - x * x.transpose());
    sid.Ct += m(a) * Pa.transpose();
    sid.Cr0 += m(a) * (skew(x) * Pa).transpose();
    for (int j = 0; j < nq; ++j) {
      const Eigen::Matrix3d pj = skew(Pa.col(j));
      sid.Cr1[j] += m(a) * pj * Pa;
      sid.J1[j] -= m(a) * (skew(x) * pj + pj * skew(x));
    }
  }
  Eigen::VectorXd mdiag(3 * N);
  for (int a = 0; a < N; ++a) mdiag.segment<3>(3 * a).setConstant(m(a));
  sid.Me = Phi.transpose() * mdiag.asDiagonal() * Phi;
  sid.Ke = Phi.transpose() * K * Phi;
  sid.De = Eigen::MatrixXd::Zero(nq, nq);
  // Oe from its definition int rho Phi^T w~ w~ x0 dV (sid.h), by sums.
  sid.Oe = Eigen::MatrixXd::Zero(nq, 6);
  for (int a = 0; a < N; ++a) {
    const Eigen::Vector3d x = X.row(a).transpose();
    const Eigen::MatrixXd Pa = Phi.middleRows(3 * a, 3);
    // w~ w~ x = w (w.x) - x |w|^2: coefficients of w1^2, w2^2, w3^2, w1 w2, w2 w3, w1 w3.
    Eigen::Matrix<double, 3, 6> G;
    G.col(0) << 0.0, -x(1), -x(2);
    G.col(1) << -x(0), 0.0, -x(2);
    G.col(2) << -x(0), -x(1), 0.0;
    G.col(3) << x(1), x(0), 0.0;
    G.col(4) << 0.0, x(2), x(1);
    G.col(5) << x(2), 0.0, x(0);
    sid.Oe += m(a) * Pa.transpose() * G;
  }
  sid.frequencies_hz.resize(nq);
  for (int i = 0; i < nq; ++i) sid.frequencies_hz(i) = std::sqrt(sid.Ke(i, i)) / (2 * M_PI);
  sid.control_points = X;
  sid.weights = Eigen::VectorXd::Ones(N);
  sid.Phi = Phi;
}

// A box of 8 point masses plus one off-centre mass, all pairs joined by axial springs of
// stiffness k (N/m). Modes: the lowest nq modes of the structure with node 0 fixed and
// node 1 fixed across the 0-1 line and node 2 along z (a tangent frame), mass-normalised;
// so Ct, Cr0 are non-zero and every coupling term of Eq. (1) is exercised.
inline FlexibleBodySid springBody(int nq, double k) {
  const int N = 9;
  Eigen::MatrixXd X(N, 3);
  X << 0, 0, 0, 0.2, 0, 0, 0, 0.12, 0, 0.2, 0.12, 0, 0, 0, 0.08, 0.2, 0, 0.08, 0, 0.12, 0.08, 0.2,
      0.12, 0.08, 0.13, 0.05, 0.03;
  Eigen::VectorXd m(N);
  m << 1.0, 1.2, 0.8, 1.1, 0.9, 1.3, 1.0, 0.7, 2.0;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * N, 3 * N);
  for (int a = 0; a < N; ++a) {
    for (int b = a + 1; b < N; ++b) {
      const Eigen::Vector3d e = (X.row(b) - X.row(a)).transpose().normalized();
      const Eigen::Matrix3d kab = k * e * e.transpose();
      K.block<3, 3>(3 * a, 3 * a) += kab;
      K.block<3, 3>(3 * b, 3 * b) += kab;
      K.block<3, 3>(3 * a, 3 * b) -= kab;
      K.block<3, 3>(3 * b, 3 * a) -= kab;
    }
  }
  // Free DOFs: all but node 0 (x, y, z), node 1 (y, z), node 2 (z).
  std::vector<int> freeDofs;
  for (int i = 0; i < 3 * N; ++i)
    if (i > 2 && i != 4 && i != 5 && i != 8) freeDofs.push_back(i);
  const int nf = static_cast<int>(freeDofs.size());
  Eigen::MatrixXd Kf(nf, nf), Mf = Eigen::MatrixXd::Zero(nf, nf);
  for (int i = 0; i < nf; ++i) {
    Mf(i, i) = m(freeDofs[i] / 3);
    for (int j = 0; j < nf; ++j) Kf(i, j) = K(freeDofs[i], freeDofs[j]);
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(Kf, Mf);
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(3 * N, nq);
  for (int j = 0; j < nq; ++j)
    for (int i = 0; i < nf; ++i) Phi(freeDofs[i], j) = eig.eigenvectors()(i, j);
  FlexibleBodySid sid;
  sid.name = "springs";
  sid.frame = ffriga::FrameKind::kTangent;
  pointMassInvariants(sid, m, X, Phi, K);
  return sid;
}

// Rigid body (nq = 0) of mass m (kg) with principal inertia diag(J) (kg m^2) about its centre
// of mass at the frame origin.
inline FlexibleBodySid rigidBody(double m, const Eigen::Vector3d& J) {
  FlexibleBodySid sid;
  sid.name = "rigid";
  sid.model = ffriga::ModelKind::kSolid;
  sid.space_dim = 3;
  sid.mass = m;
  sid.inertia = J.asDiagonal();
  sid.Me = sid.Ke = sid.De = Eigen::MatrixXd(0, 0);
  sid.Ct = sid.Cr0 = Eigen::MatrixXd(0, 3);
  sid.Oe = Eigen::MatrixXd(0, 6);
  sid.control_points = Eigen::MatrixXd(0, 3);
  sid.Phi = Eigen::MatrixXd(0, 0);
  return sid;
}

}  // namespace ffriga::test
