#include "common/splines/extracted_surface.h"

#include <algorithm>
#include <cmath>

#include "common/base/error.h"
#include "common/splines/rational_basis.h"

namespace ffriga {

void bernsteinBasis(int p, double t, int order, Eigen::MatrixXd& out) {
  // Values of degree p - r by the triangular recursion B_{i,k} = (1-t) B_{i,k-1} + t B_{i-1,k-1};
  // derivatives: d/dt B_{i,p} = p (B_{i-1,p-1} - B_{i,p-1}) applied r times.
  // Hot path of the contact search: no heap allocation beyond `out` (reused if sized).
  constexpr int kMaxDegree = 24;
  FFRIGA_CHECK(p >= 0 && p <= kMaxDegree, "Bernstein degree " << p << " outside 0.." << kMaxDegree);
  out.setZero(order + 1, p + 1);
  double level[kMaxDegree + 1][kMaxDegree + 1];
  level[0][0] = 1.0;
  for (int k = 1; k <= p; ++k) {
    for (int i = 0; i <= k; ++i) {
      const double left = i < k ? level[k - 1][i] : 0.0;
      const double right = i > 0 ? level[k - 1][i - 1] : 0.0;
      level[k][i] = (1.0 - t) * left + t * right;
    }
  }
  for (int r = 0; r <= order && r <= p; ++r) {
    // Coefficients of the r-th derivative in the basis of degree p - r: finite differences.
    const double* low = level[p - r];
    double factor = 1.0;
    for (int j = 0; j < r; ++j) factor *= p - j;
    for (int i = 0; i <= p; ++i) {
      double sum = 0.0;
      // d^r B_{i,p} = p!/(p-r)! sum_j (-1)^(r-j) C(r,j) B_{i-j, p-r}
      double binom = 1.0;
      for (int j = 0; j <= r; ++j) {
        const int idx = i - j;
        if (idx >= 0 && idx <= p - r) sum += ((r - j) % 2 == 0 ? 1.0 : -1.0) * binom * low[idx];
        binom = binom * (r - j) / (j + 1);
      }
      out(r, i) = factor * sum;
    }
  }
}

ExtractedSurface::ExtractedSurface(const ContactSurface& surface, const Eigen::VectorXd& weights)
    : surface_(&surface), dim_(surface.dim) {
  FFRIGA_CHECK(dim_ == 1 || dim_ == 2, "surface '" << surface.name << "' has dim " << dim_);
  FFRIGA_CHECK(static_cast<int>(surface.degrees.size()) == dim_,
               "surface '" << surface.name << "': " << surface.degrees.size() << " degrees");
  const int ne = static_cast<int>(surface.element_lower.rows());
  FFRIGA_CHECK(ne > 0 && surface.element_upper.rows() == ne &&
                   surface.element_lower.cols() == dim_ &&
                   static_cast<int>(surface.function_offsets.size()) == ne + 1 &&
                   static_cast<int>(surface.extraction.size()) == ne,
               "surface '" << surface.name << "': inconsistent element arrays");
  int nb = 1;
  for (int p : surface.degrees) nb *= p + 1;
  lower_ = surface.element_lower;
  upper_ = surface.element_upper;
  domain_lo_ = lower_.colwise().minCoeff().transpose();
  domain_hi_ = upper_.colwise().maxCoeff().transpose();
  element_weights_.resize(ne);
  for (int e = 0; e < ne; ++e) {
    const int n = numFunctions(e);
    FFRIGA_CHECK(surface.extraction[e].rows() == n && surface.extraction[e].cols() == nb,
                 "surface '" << surface.name << "' element " << e << ": extraction operator is "
                             << surface.extraction[e].rows() << "x" << surface.extraction[e].cols()
                             << ", expected " << n << "x" << nb);
    for (int a = 0; a < dim_; ++a) {
      FFRIGA_CHECK(upper_(e, a) > lower_(e, a),
                   "surface '" << surface.name << "' element " << e << ": empty box");
    }
    element_weights_[e].resize(n);
    for (int i = 0; i < n; ++i) {
      const int k = functions(e)[i];
      FFRIGA_CHECK(k >= 0 && k < weights.size(),
                   "surface '" << surface.name << "': function " << k << " out of range");
      element_weights_[e](i) = weights(k);
      all_functions_.push_back(k);
    }
  }
  std::sort(all_functions_.begin(), all_functions_.end());
  all_functions_.erase(std::unique(all_functions_.begin(), all_functions_.end()),
                       all_functions_.end());
}

int ExtractedSurface::findElement(const double* s) const {
  for (int e = 0; e < numElements(); ++e) {
    bool inside = true;
    for (int a = 0; a < dim_ && inside; ++a) inside = s[a] >= lower_(e, a) && s[a] <= upper_(e, a);
    if (inside) return e;
  }
  return -1;
}

void ExtractedSurface::basis(int e, const double* s, int order, Eigen::MatrixXd& R) const {
  // Workspaces per thread and derivative order: the contact search calls this millions of
  // times from an OpenMP loop with alternating orders (Newton 2, line search 0), and Eigen
  // reuses storage of the same size without allocating.
  thread_local Eigen::MatrixXd b0Of[3], b1Of[3], bernOf[3], BOf[3];
  const int slot = std::min(order, 2);
  Eigen::MatrixXd &b0 = b0Of[slot], &b1 = b1Of[slot], &bern = bernOf[slot], &B = BOf[slot];
  const std::vector<int>& p = surface_->degrees;
  const int rows = numDerivativeRows(dim_, order);
  const double h0 = upper_(e, 0) - lower_(e, 0);
  bernsteinBasis(p[0], (s[0] - lower_(e, 0)) / h0, order, b0);
  for (int r = 1; r <= order; ++r) b0.row(r) /= std::pow(h0, r);
  if (dim_ == 1) {
    B.noalias() = b0.topRows(rows) * surface_->extraction[e].transpose();
  } else {
    const double h1 = upper_(e, 1) - lower_(e, 1);
    bernsteinBasis(p[1], (s[1] - lower_(e, 1)) / h1, order, b1);
    for (int r = 1; r <= order; ++r) b1.row(r) /= std::pow(h1, r);
    const int n0 = p[0] + 1, n1 = p[1] + 1;
    bern.resize(rows, n0 * n1);
    // Derivative orders (r0, r1) of each table row for dc = 2.
    static const int kOrders[6][2] = {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}};
    for (int row = 0; row < rows; ++row) {
      for (int j = 0; j < n1; ++j)
        for (int i = 0; i < n0; ++i)
          bern(row, i + n0 * j) = b0(kOrders[row][0], i) * b1(kOrders[row][1], j);
    }
    B.noalias() = bern * surface_->extraction[e].transpose();
  }
  rationalize(B, element_weights_[e], dim_, order, R);
}

void ExtractedSurface::evaluate(int e, const double* s, const Eigen::MatrixXd& points, int order,
                                SurfacePoint& out) const {
  thread_local Eigen::MatrixXd ROf[3];  // per order, as in basis()
  Eigen::MatrixXd& R = ROf[std::min(order, 2)];
  basis(e, s, order, R);
  pointFromTable(R, functions(e), points, dim_, order, out);
}

Eigen::VectorXd ExtractedSurface::normal(const Eigen::MatrixXd& dx) const {
  Eigen::VectorXd n;
  normal(dx, n);
  return n;
}

void ExtractedSurface::normal(const Eigen::MatrixXd& dx, Eigen::VectorXd& n) const {
  if (dim_ == 2) {
    const Eigen::Vector3d a = dx.col(0), b = dx.col(1);
    n = a.cross(b);
  } else {
    n.resize(2);
    n << dx(1, 0), -dx(0, 0);
  }
  n = surface_->outward_sign * n / n.norm();
}

}  // namespace ffriga
