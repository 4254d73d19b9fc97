#include "preproc/reduction/characteristic_constraint_modes.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "common/base/error.h"

namespace ffriga {

namespace {

// Eigenvalues at or below this fraction of the largest are zero: the solver's absolute error
// is round-off times the largest (~1e-16), and the lowest elastic eigenvalue of a region
// lies far above it (2.5e-7 of the largest for 10 um elements on a 1 cm sphere, about
// (element size / body size)^2).
constexpr double kZeroEigenvalue = 1e-11;
// Eigenvalues within this relative distance belong to one cluster (the degenerate pairs of
// a symmetric region agree to round-off; distinct ones differ by far more).
constexpr double kCluster = 1e-6;

Eigen::MatrixXd block(const Eigen::MatrixXd& A, const std::vector<int>& rows,
                      const std::vector<int>& cols) {
  Eigen::MatrixXd B(rows.size(), cols.size());
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < cols.size(); ++j) B(i, j) = A(rows[i], cols[j]);
  return B;
}

// The number of modes kept: every zero one, then `count` elastic ones, then the rest of the
// last cluster.
int modesKept(const Eigen::VectorXd& lambda, int count, int* rigid) {
  const int n = static_cast<int>(lambda.size());
  const double top = std::max(lambda.maxCoeff(), 0.0);
  int zero = 0;
  while (zero < n && lambda(zero) <= kZeroEigenvalue * top) ++zero;
  int kept = std::min(n, zero + count);
  while (kept > zero && kept < n && lambda(kept) - lambda(kept - 1) <= kCluster * lambda(kept - 1))
    ++kept;
  *rigid = zero;
  return kept;
}

// The columns of Q made M-orthonormal (Q^T M Q = E): scaled to unit M-norm, then directions
// whose Gram eigenvalue lies below kDependent dropped: combinations of unit columns shorter
// than 1e-6 (nearly parallel static responses of neighbouring patch radii, or moments the
// collocation points cannot tell apart on the smallest patches), still 1e4 above the
// round-off of the Gram matrix (~1e-16 times the columns). An absolute bound: what one
// region keeps does not depend on the other regions' columns.
constexpr double kDependent = 1e-12;

Eigen::MatrixXd orthonormalColumns(Eigen::MatrixXd Q, const Eigen::MatrixXd& M) {
  // Unit M-norm columns first: static responses are metres per newton, modes are not.
  for (int j = 0; j < Q.cols(); ++j) {
    const double norm = std::sqrt(Q.col(j).dot(M * Q.col(j)));
    if (norm > 0.0) Q.col(j) /= norm;
  }
  Eigen::MatrixXd G = Q.transpose() * M * Q;
  G = 0.5 * (G + G.transpose()).eval();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(G);
  if (eig.info() != Eigen::Success)
    throw ComputeError("interface reduction: orthonormalising the pressure patch responses failed");
  std::vector<int> keep;
  for (int j = static_cast<int>(G.rows()) - 1; j >= 0; --j)  // the largest first
    if (eig.eigenvalues()(j) > kDependent) keep.push_back(j);
  Eigen::MatrixXd out(Q.rows(), keep.size());
  for (std::size_t j = 0; j < keep.size(); ++j)
    out.col(j) = Q * eig.eigenvectors().col(keep[j]) / std::sqrt(eig.eigenvalues()(keep[j]));
  return out;
}

// The rows of interface loads (nb x P) that belong to the region (indices into Mr).
Eigen::MatrixXd regionRows(const Eigen::MatrixXd& loads, const std::vector<int>& region, int nm) {
  Eigen::MatrixXd F(region.size(), loads.cols());
  for (std::size_t i = 0; i < region.size(); ++i) F.row(i) = loads.row(region[i] - nm);
  return F;
}

// u = K_cc^+ f through the elastic spectrum (V M_cc-orthonormal, the first `rigid` zero).
Eigen::MatrixXd staticResponses(const Eigen::MatrixXd& V, const Eigen::VectorXd& lambda, int rigid,
                                const Eigen::MatrixXd& F) {
  const int elastic = static_cast<int>(lambda.size()) - rigid;
  const Eigen::MatrixXd Ve = V.rightCols(elastic);
  const Eigen::VectorXd inverse = lambda.tail(elastic).cwiseInverse();
  return Ve * (inverse.asDiagonal() * (Ve.transpose() * F));
}

}  // namespace

InterfaceReduction characteristicConstraintModes(const Eigen::MatrixXd& Mr,
                                                 const Eigen::MatrixXd& Kr, int nm,
                                                 const std::vector<bool>& retained, int count,
                                                 const Eigen::MatrixXd& loads,
                                                 const Eigen::MatrixXd& check_loads) {
  const int nb = static_cast<int>(retained.size());
  FFRIGA_CHECK(Mr.rows() == nm + nb && Kr.rows() == nm + nb && count >= 0 &&
                   (count >= 1 || loads.cols() > 0) && (loads.cols() == 0 || loads.rows() == nb),
               "interface reduction: " << Mr.rows() << " reduced coordinates, " << nm << " + " << nb
                                       << " expected, count " << count);
  std::vector<int> region, kept_dofs;  // indices into Mr, Kr
  for (int k = 0; k < nb; ++k) (retained[k] ? kept_dofs : region).push_back(nm + k);
  const int nc = static_cast<int>(region.size());
  const int nk = static_cast<int>(kept_dofs.size());
  InterfaceReduction out;
  out.retained = nk;
  Eigen::MatrixXd V;  // nc x nc, M_cc-orthonormal eigenvectors, ascending
  const Eigen::MatrixXd Mcc = block(Mr, region, region), Kcc = block(Kr, region, region);
  if (nc > 0) {
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(Kcc, Mcc,
                                                                  Eigen::ComputeEigenvectors);
    if (eig.info() != Eigen::Success) {
      throw ComputeError(
          "interface reduction: the characteristic constraint modes' eigen solve failed (is "
          "the contact region's condensed mass positive definite?)");
    }
    out.omega2 = eig.eigenvalues();
    V = eig.eigenvectors();
  }
  const int modes = nc > 0 ? modesKept(out.omega2, count, &out.rigid) : 0;
  out.elastic = modes - out.rigid;
  // The region's basis: the elastic characteristic modes kept and the static responses to
  // the loads, u = K_cc^+ f_c (through the elastic spectrum: the loads' rigid part is
  // balanced by inertia, as on a free body), made M_cc-orthonormal together.
  Eigen::MatrixXd Q = V.middleCols(out.rigid, out.elastic);
  if (loads.cols() > 0 && nc > 0) {
    Eigen::MatrixXd QU(nc, Q.cols() + loads.cols());
    QU << Q, staticResponses(V, out.omega2, out.rigid, regionRows(loads, region, nm));
    Q = orthonormalColumns(QU, Mcc);
    out.patch_modes = static_cast<int>(Q.cols()) - out.elastic;
  }
  if (check_loads.cols() > 0 && nc > 0) {
    const Eigen::MatrixXd G = regionRows(check_loads, region, nm);
    const Eigen::MatrixXd U = staticResponses(V, out.omega2, out.rigid, G);
    const Eigen::MatrixXd QtG = Q.transpose() * G;
    const Eigen::MatrixXd KQ = Q.transpose() * Kcc * Q;
    const Eigen::MatrixXd UQ = KQ.ldlt().solve(QtG);
    out.compliance_error.resize(G.cols());
    for (int i = 0; i < G.cols(); ++i) {
      const double c = G.col(i).dot(U.col(i)), cQ = QtG.col(i).dot(UQ.col(i));
      out.compliance_error(i) = c > 0.0 ? 1.0 - cQ / c : 0.0;
    }
  }
  // The zero modes are rigid motions of the whole body (constraint modes of a rigid interface
  // motion), which the frame projection removes: they are left out of T.
  const int regionCols = static_cast<int>(Q.cols());
  out.T.setZero(nm + nb, nm + regionCols + nk);
  out.T.topLeftCorner(nm, nm).setIdentity();
  for (int j = 0; j < regionCols; ++j)
    for (int i = 0; i < nc; ++i) out.T(region[i], nm + j) = Q(i, j);
  if (nk > 0 && nc > 0) {
    // The region's static response to a unit displacement of each retained DOF, through the
    // elastic part of the spectrum (a zero-mode part would be a rigid motion of the body,
    // which the frame projection removes: header comment).
    const Eigen::MatrixXd S =
        -staticResponses(V, out.omega2, out.rigid, block(Kr, region, kept_dofs));
    for (int m = 0; m < nk; ++m)
      for (int i = 0; i < nc; ++i) out.T(region[i], nm + regionCols + m) = S(i, m);
  }
  for (int m = 0; m < nk; ++m) out.T(kept_dofs[m], nm + regionCols + m) = 1.0;
  return out;
}

}  // namespace ffriga
