#include "common/splines/nurbs_patch.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "common/splines/bspline_basis.h"
#include "common/base/error.h"

namespace ffriga {

NurbsPatch::NurbsPatch(std::vector<KnotVector> knots, Eigen::MatrixXd points,
                       Eigen::VectorXd weights)
    : knots_(std::move(knots)), points_(std::move(points)), weights_(std::move(weights)) {
  const int d = paramDim();
  if (d < 1 || d > 3) {
    throw std::invalid_argument(Str() << "a patch needs 1 to 3 parametric directions, found " << d);
  }
  if (spaceDim() < 2 || spaceDim() > 3) {
    throw std::invalid_argument(Str()
                                << "control points need 2 or 3 coordinates, found " << spaceDim());
  }
  int n = 1;
  for (const auto& U : knots_) n *= U.numBasis();
  if (points_.rows() != n) {
    throw std::invalid_argument(Str() << "the knot vectors define " << n << " basis functions but "
                                      << points_.rows() << " control points were given");
  }
  if (weights_.size() != n) {
    throw std::invalid_argument(Str() << "the knot vectors define " << n << " basis functions but "
                                      << weights_.size() << " weights were given");
  }
  for (int k = 0; k < n; ++k) {
    if (!(weights_(k) > 0.0)) {
      throw std::invalid_argument(Str() << "weight " << k << " is " << weights_(k)
                                        << ", weights must be positive");
    }
  }
}

int NurbsPatch::numElements() const {
  int e = 1;
  for (const auto& U : knots_) e *= U.numElements();
  return e;
}

int NurbsPatch::linearIndex(const std::array<int, 3>& i) const {
  int k = 0;
  for (int dir = paramDim() - 1; dir >= 0; --dir) k = k * numBasis(dir) + i[dir];
  return k;
}

std::array<int, 3> NurbsPatch::tensorIndex(int k) const {
  std::array<int, 3> i{0, 0, 0};
  for (int dir = 0; dir < paramDim(); ++dir) {
    i[dir] = k % numBasis(dir);
    k /= numBasis(dir);
  }
  return i;
}

Eigen::MatrixXd NurbsPatch::homogeneous() const {
  Eigen::MatrixXd Pw(numControlPoints(), spaceDim() + 1);
  Pw.leftCols(spaceDim()) = weights_.asDiagonal() * points_;
  Pw.col(spaceDim()) = weights_;
  return Pw;
}

NurbsPatch NurbsPatch::fromHomogeneous(std::vector<KnotVector> knots, const Eigen::MatrixXd& Pw) {
  const int s = static_cast<int>(Pw.cols()) - 1;
  Eigen::VectorXd w = Pw.col(s);
  Eigen::MatrixXd P = w.cwiseInverse().asDiagonal() * Pw.leftCols(s);
  return NurbsPatch(std::move(knots), std::move(P), std::move(w));
}

void tensorBasis(const std::vector<KnotVector>& knots, const int* spans, const double* xi,
                 int order, Eigen::MatrixXd& table) {
  const int d = static_cast<int>(knots.size());
  FFRIGA_ASSERT(order >= 0 && order <= 2, "order = " << order);
  // Univariate derivatives per direction: ders[dir][k * (p+1) + j].
  double ders[3][3 * (kMaxDegree + 1)];
  int nfun[3] = {1, 1, 1};
  for (int dir = 0; dir < d; ++dir) {
    basisFunctionDerivatives(knots[dir], spans[dir], xi[dir], order, ders[dir]);
    nfun[dir] = knots[dir].degree() + 1;
  }
  const int rows = numDerivativeRows(d, order);
  const int cols = nfun[0] * nfun[1] * nfun[2];
  table.resize(rows, cols);
  // Derivative order per direction of each row.
  int orders[10][3] = {};
  for (int a = 0; a < d && order >= 1; ++a) orders[1 + a][a] = 1;
  if (order >= 2) {
    for (int a = 0; a < d; ++a) {
      for (int b = a; b < d; ++b) {
        const int r = secondDerivativeRow(d, a, b);
        orders[r][a] += 1;
        orders[r][b] += 1;
      }
    }
  }
  int c = 0;
  for (int j2 = 0; j2 < nfun[2]; ++j2) {
    for (int j1 = 0; j1 < nfun[1]; ++j1) {
      for (int j0 = 0; j0 < nfun[0]; ++j0, ++c) {
        const int j[3] = {j0, j1, j2};
        for (int r = 0; r < rows; ++r) {
          double v = 1.0;
          for (int dir = 0; dir < d; ++dir) v *= ders[dir][orders[r][dir] * nfun[dir] + j[dir]];
          table(r, c) = v;
        }
      }
    }
  }
}

void NurbsPatch::bsplineBasis(const double* xi, int order, PatchBasis& out) const {
  int spans[3] = {0, 0, 0};
  for (int dir = 0; dir < paramDim(); ++dir) spans[dir] = knots_[dir].findSpan(xi[dir]);
  bsplineBasisOnSpans(spans, xi, order, out);
}

void NurbsPatch::bsplineBasisOnSpans(const int* spans, const double* xi, int order,
                                     PatchBasis& out) const {
  const int d = paramDim();
  tensorBasis(knots_, spans, xi, order, out.table);
  out.index.resize(out.table.cols());
  int c = 0;
  const int p0 = degree(0);
  const int p1 = d > 1 ? degree(1) : 0;
  const int p2 = d > 2 ? degree(2) : 0;
  for (int j2 = 0; j2 <= p2; ++j2) {
    for (int j1 = 0; j1 <= p1; ++j1) {
      for (int j0 = 0; j0 <= p0; ++j0, ++c) {
        out.index[c] = linearIndex(
            {spans[0] - p0 + j0, d > 1 ? spans[1] - p1 + j1 : 0, d > 2 ? spans[2] - p2 + j2 : 0});
      }
    }
  }
}

void NurbsPatch::rationalBasisOnSpans(const int* spans, const double* xi, int order,
                                      PatchBasis& out) const {
  PatchBasis poly;
  bsplineBasisOnSpans(spans, xi, order, poly);
  Eigen::VectorXd w(poly.index.size());
  for (int c = 0; c < w.size(); ++c) w(c) = weights_(poly.index[c]);
  rationalize(poly.table, w, paramDim(), order, out.table);
  out.index = std::move(poly.index);
}

void NurbsPatch::basis(const double* xi, int order, PatchBasis& out) const {
  int spans[3] = {0, 0, 0};
  for (int dir = 0; dir < paramDim(); ++dir) spans[dir] = knots_[dir].findSpan(xi[dir]);
  rationalBasisOnSpans(spans, xi, order, out);
}

void pointFromTable(const Eigen::MatrixXd& table, const int* functions,
                    const Eigen::MatrixXd& points, int d, int order, PatchPoint& pt) {
  // Per-thread workspace per order (storage reused: the contact search alternates orders).
  thread_local Eigen::MatrixXd XOf[3];
  Eigen::MatrixXd& X = XOf[std::min(order, 2)];
  X.setZero(table.rows(), points.cols());
  for (int i = 0; i < table.cols(); ++i) X.noalias() += table.col(i) * points.row(functions[i]);
  pt.x = X.row(0).transpose();
  if (order >= 1) pt.dx = X.middleRows(1, d).transpose();
  if (order >= 2) pt.ddx = X.middleRows(1 + d, d * (d + 1) / 2).transpose();
}

PatchPoint pointFromTable(const Eigen::MatrixXd& table, const int* functions,
                          const Eigen::MatrixXd& points, int d, int order) {
  PatchPoint pt;
  pointFromTable(table, functions, points, d, order, pt);
  return pt;
}

PatchPoint NurbsPatch::evaluate(const double* xi, int order) const {
  PatchBasis R;
  basis(xi, order, R);
  return pointFromTable(R.table, R.index.data(), points_, paramDim(), order);
}

std::vector<std::vector<int>> coincidentPoints(const Eigen::MatrixXd& P, double tol) {
  const int n = static_cast<int>(P.rows());
  // Sort by the first coordinate, then compare neighbours within tol (union-find).
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return P(a, 0) < P(b, 0); });
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n && P(order[b], 0) - P(order[a], 0) <= tol; ++b) {
      if ((P.row(order[a]) - P.row(order[b])).lpNorm<Eigen::Infinity>() <= tol) {
        const int ra = find(order[a]);
        const int rb = find(order[b]);
        parent[std::max(ra, rb)] = std::min(ra, rb);
      }
    }
  }
  std::vector<std::vector<int>> groups(n);
  for (int k = 0; k < n; ++k) groups[find(k)].push_back(k);
  std::vector<std::vector<int>> result;
  for (auto& g : groups) {
    if (g.size() >= 2) result.push_back(std::move(g));
  }
  std::sort(result.begin(), result.end());
  return result;
}

std::vector<std::vector<int>> coincidentControlPoints(const NurbsPatch& patch, double tol) {
  return coincidentPoints(patch.points(), tol);
}

}  // namespace ffriga
