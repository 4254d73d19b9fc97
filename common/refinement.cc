#include "common/refinement.h"

#include <algorithm>
#include <stdexcept>

#include "common/bspline_basis.h"
#include "common/error.h"

namespace ffriga {

Eigen::MatrixXd knotInsertionMatrix(const KnotVector& U, const std::vector<double>& X,
                                    KnotVector* refined) {
  const int p = U.degree();
  std::vector<double> knots = U.knots();
  const int n0 = U.numBasis();
  Eigen::MatrixXd T = Eigen::MatrixXd::Identity(n0, n0);
  std::vector<double> sorted = X;
  std::sort(sorted.begin(), sorted.end());
  for (double u : sorted) {
    if (!(u >= knots.front() && u <= knots.back())) {
      throw std::invalid_argument(Str() << "knot " << u << " lies outside the parameter domain ["
                                        << knots.front() << ", " << knots.back() << "]");
    }
    // Boehm: span k with u_k <= u < u_{k+1} (u = back goes to the last span).
    const KnotVector current(knots, p);
    const int k = current.findSpan(u);
    const int s = current.multiplicity(u);
    const bool interior = u > knots.front() && u < knots.back();
    if (!interior) {
      throw std::invalid_argument(Str() << "knot " << u << " is an end of the domain, where a "
                                        << "clamped knot vector already has full multiplicity");
    }
    if (s + 1 > p) {
      throw std::invalid_argument(Str() << "inserting knot " << u << " would give it multiplicity "
                                        << s + 1 << ", at most the degree " << p << " is allowed");
    }
    const int n = current.numBasis();
    Eigen::MatrixXd Tn(n + 1, T.cols());
    // Pbar_i = P_i (i <= k - p), alpha_i P_i + (1 - alpha_i) P_{i-1} (k-p+1 <= i <= k - s),
    // P_{i-1} (i >= k - s + 1).
    for (int i = 0; i <= k - p; ++i) Tn.row(i) = T.row(i);
    for (int i = k - p + 1; i <= k - s; ++i) {
      const double alpha = (u - knots[i]) / (knots[i + p] - knots[i]);
      Tn.row(i) = alpha * T.row(i) + (1.0 - alpha) * T.row(i - 1);
    }
    for (int i = k - s + 1; i <= n; ++i) Tn.row(i) = T.row(i - 1);
    T.swap(Tn);
    knots.insert(knots.begin() + k + 1, u);
  }
  if (refined) *refined = KnotVector(std::move(knots), p);
  return T;
}

Eigen::MatrixXd degreeElevationMatrix(const KnotVector& U, int t, KnotVector* elevated) {
  FFRIGA_CHECK(t >= 0, "t = " << t);
  const int p = U.degree();
  if (p + t > kMaxDegree) {
    throw std::invalid_argument(Str() << "elevating degree " << p << " by " << t
                                      << " exceeds the supported maximum degree " << kMaxDegree);
  }
  std::vector<double> knots;
  for (double b : U.breaks()) knots.insert(knots.end(), U.multiplicity(b) + t, b);
  KnotVector E(std::move(knots), p + t);
  const int n = U.numBasis();
  const int m = E.numBasis();
  // Collocation at the Greville abscissae tau_k of the elevated space:
  //   sum_j Nbar_j(tau_k) T(j, i) = N_i(tau_k).
  const std::vector<double> tau = E.greville();
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(m, m);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(m, n);
  double Nbar[kMaxDegree + 1];
  double N[kMaxDegree + 1];
  for (int k = 0; k < m; ++k) {
    const int sb = E.findSpan(tau[k]);
    basisFunctions(E, sb, tau[k], Nbar);
    for (int j = 0; j <= p + t; ++j) B(k, sb - p - t + j) = Nbar[j];
    const int s = U.findSpan(tau[k]);
    basisFunctions(U, s, tau[k], N);
    for (int j = 0; j <= p; ++j) A(k, s - p + j) = N[j];
  }
  Eigen::MatrixXd T = B.fullPivLu().solve(A);
  // Entries are exactly zero outside the supports; clean round-off there.
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < n; ++i) {
      if (E[j + p + t + 1] <= U[i] || E[j] >= U[i + p + 1]) T(j, i) = 0.0;
    }
  }
  if (elevated) *elevated = std::move(E);
  return T;
}

Eigen::SparseMatrix<double> refinementMatrix(const KnotVector& coarse, const KnotVector& fine) {
  if (coarse.degree() != fine.degree() || coarse.front() != fine.front() ||
      coarse.back() != fine.back()) {
    throw std::invalid_argument("refinementMatrix: knot vectors differ in degree or domain");
  }
  // Multiset difference fine \ coarse.
  std::vector<double> X;
  std::size_t i = 0;
  for (double u : fine.knots()) {
    if (i < coarse.knots().size() && coarse.knots()[i] == u) {
      ++i;
    } else {
      X.push_back(u);
    }
  }
  if (i != coarse.knots().size()) {
    throw std::invalid_argument(Str() << "refinementMatrix: coarse knot " << coarse.knots()[i]
                                      << " is missing from the fine knot vector");
  }
  KnotVector check;
  const Eigen::MatrixXd T = knotInsertionMatrix(coarse, X, &check);
  return T.sparseView(1.0, 0.0);
}

std::vector<double> uniformInsertionKnots(const KnotVector& U, int perSpan) {
  FFRIGA_CHECK(perSpan >= 0, "perSpan = " << perSpan);
  std::vector<double> X;
  const std::vector<double> b = U.breaks();
  for (std::size_t e = 0; e + 1 < b.size(); ++e) {
    for (int k = 1; k <= perSpan; ++k) {
      X.push_back(b[e] + (b[e + 1] - b[e]) * k / (perSpan + 1));
    }
  }
  return X;
}

NurbsPatch applyAlongDirection(const NurbsPatch& patch, int dir, const Eigen::MatrixXd& T,
                               const KnotVector& newKnots) {
  const int d = patch.paramDim();
  FFRIGA_CHECK(dir >= 0 && dir < d, "dir = " << dir);
  FFRIGA_CHECK(T.cols() == patch.numBasis(dir) && T.rows() == newKnots.numBasis(),
               "T is " << T.rows() << "x" << T.cols());
  const Eigen::MatrixXd Pw = patch.homogeneous();
  std::vector<KnotVector> knots = patch.knotVectors();
  knots[dir] = newKnots;
  // Strides: lines along `dir` are indexed by (before, after).
  int before = 1;
  int after = 1;
  for (int a = 0; a < dir; ++a) before *= patch.numBasis(a);
  for (int a = dir + 1; a < d; ++a) after *= patch.numBasis(a);
  const int n = patch.numBasis(dir);
  const int nbar = static_cast<int>(T.rows());
  Eigen::MatrixXd Qw(before * nbar * after, Pw.cols());
  Eigen::MatrixXd line(n, Pw.cols());
  for (int c = 0; c < after; ++c) {
    for (int a = 0; a < before; ++a) {
      for (int i = 0; i < n; ++i) line.row(i) = Pw.row(a + before * (i + n * c));
      const Eigen::MatrixXd fine = T * line;
      for (int j = 0; j < nbar; ++j) Qw.row(a + before * (j + nbar * c)) = fine.row(j);
    }
  }
  return NurbsPatch::fromHomogeneous(std::move(knots), Qw);
}

NurbsPatch insertKnots(const NurbsPatch& patch, int dir, const std::vector<double>& X) {
  KnotVector refined;
  const Eigen::MatrixXd T = knotInsertionMatrix(patch.knots(dir), X, &refined);
  return applyAlongDirection(patch, dir, T, refined);
}

NurbsPatch elevateDegree(const NurbsPatch& patch, int dir, int t) {
  KnotVector elevated;
  const Eigen::MatrixXd T = degreeElevationMatrix(patch.knots(dir), t, &elevated);
  return applyAlongDirection(patch, dir, T, elevated);
}

}  // namespace ffriga
