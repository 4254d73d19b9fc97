#include "common/splines/refinement.h"

#include <algorithm>
#include <stdexcept>

#include "common/splines/bspline_basis.h"
#include "common/base/error.h"

namespace ffriga {

Eigen::MatrixXd knotInsertionMatrix(const KnotVector& U, const std::vector<double>& X,
                                    KnotVector* refined) {
  const int p = U.degree();
  const std::vector<double>& u = U.knots();
  std::vector<double> x = X;
  std::sort(x.begin(), x.end());
  // Checks first: inside the domain, interior, final multiplicity at most p.
  for (std::size_t j = 0; j < x.size(); ++j) {
    if (!(x[j] >= u.front() && x[j] <= u.back())) {
      throw std::invalid_argument(Str() << "knot " << x[j] << " lies outside the parameter domain ["
                                        << u.front() << ", " << u.back() << "]");
    }
    if (x[j] == u.front() || x[j] == u.back()) {
      throw std::invalid_argument(Str() << "knot " << x[j] << " is an end of the domain, where a "
                                        << "clamped knot vector already has full multiplicity");
    }
    if (j == 0 || x[j] != x[j - 1]) {
      const int mult =
          U.multiplicity(x[j]) + static_cast<int>(std::count(x.begin() + j, x.end(), x[j]));
      if (mult > p) {
        throw std::invalid_argument(Str()
                                    << "inserting knot " << x[j] << " would give it multiplicity "
                                    << mult << ", at most the degree " << p << " is allowed");
      }
    }
  }
  const int n0 = U.numBasis();
  if (x.empty()) {
    if (refined) *refined = U;
    return Eigen::MatrixXd::Identity(n0, n0);
  }
  // Piegl & Tiller A5.4 (RefineKnotVectCurve) applied to the rows of the identity: the
  // coefficient rows Q of the fine functions, each a combination of the coarse ones.
  // Row-major, so that every row operation touches contiguous memory.
  using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const int n = n0 - 1;  // P&T's n: index of the last control point
  const int m = n + p + 1;
  const int r = static_cast<int>(x.size()) - 1;
  const int a = U.findSpan(x.front());
  const int b = U.findSpan(x.back()) + 1;
  RowMatrix Q = RowMatrix::Zero(n0 + r + 1, n0);
  std::vector<double> ubar(u.size() + x.size());
  for (int j = 0; j <= a - p; ++j) Q(j, j) = 1.0;
  for (int j = b - 1; j <= n; ++j) Q(j + r + 1, j) = 1.0;
  for (int j = 0; j <= a; ++j) ubar[j] = u[j];
  for (int j = b + p; j <= m; ++j) ubar[j + r + 1] = u[j];
  int i = b + p - 1;
  int k = b + p + r;
  for (int j = r; j >= 0; --j) {
    while (x[j] <= u[i] && i > a) {
      Q.row(k - p - 1).setZero();
      Q(k - p - 1, i - p - 1) = 1.0;
      ubar[k] = u[i];
      --k;
      --i;
    }
    Q.row(k - p - 1) = Q.row(k - p);
    for (int l = 1; l <= p; ++l) {
      const int ind = k - p + l;
      double alpha = ubar[k + l] - x[j];
      if (alpha == 0.0) {
        Q.row(ind - 1) = Q.row(ind);
      } else {
        alpha /= ubar[k + l] - u[i - p + l];
        Q.row(ind - 1) = alpha * Q.row(ind - 1) + (1.0 - alpha) * Q.row(ind);
      }
    }
    ubar[k] = x[j];
    --k;
  }
  if (refined) *refined = KnotVector(std::move(ubar), p);
  return Q;
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
