#include "common/extracted_surface.h"

#include "common/error.h"
#include "common/rational_basis.h"

namespace ffriga {

void bernsteinDerivatives(int p, double t, int order, double* ders) {
  FFRIGA_CHECK(p >= 0 && p <= kMaxDegree && order >= 0 && order <= 2, "p " << p);
  // Bern_{b,q}(t) for q = p, p-1, p-2 by the de Casteljau-type recurrence, then
  // d/dt Bern_{b,p} = p (Bern_{b-1,p-1} - Bern_{b,p-1}) and its repetition.
  double B[3][kMaxDegree + 1];  // degrees p, p-1, p-2
  auto bernsteinAll = [t](int q, double* out) {
    out[0] = 1.0;
    for (int j = 1; j <= q; ++j) {
      double saved = 0.0;
      for (int b = 0; b < j; ++b) {
        const double tmp = out[b];
        out[b] = saved + (1.0 - t) * tmp;
        saved = t * tmp;
      }
      out[j] = saved;
    }
  };
  for (int k = 0; k <= order && k <= p; ++k) bernsteinAll(p - k, B[k]);
  for (int k = 0; k <= order; ++k) {
    for (int b = 0; b <= p; ++b) {
      double v = 0.0;
      if (k == 0) {
        v = B[0][b];
      } else if (k <= p) {
        // k-th derivative: p!/(p-k)! sum_i (-1)^(k-i) C(k, i) Bern_{b-i, p-k}
        double f = 1.0;
        for (int i = 0; i < k; ++i) f *= p - i;
        const int binom[3][3] = {{1, 0, 0}, {1, 1, 0}, {1, 2, 1}};
        for (int i = 0; i <= k; ++i) {
          const int j = b - i;
          if (j < 0 || j > p - k) continue;
          v += ((k - i) % 2 ? -1.0 : 1.0) * binom[k][i] * B[k][j];
        }
        v *= f;
      }
      ders[k * (p + 1) + b] = v;
    }
  }
}

ExtractedSurface::ExtractedSurface(const ContactSurface& surface, Eigen::MatrixXd points,
                                   Eigen::VectorXd weights)
    : surface_(surface), points_(std::move(points)), weights_(std::move(weights)) {
  FFRIGA_CHECK(points_.rows() == weights_.size(), "points " << points_.rows());
  FFRIGA_CHECK(surface_.dim == 1 || surface_.dim == 2, "dim " << surface_.dim);
}

void ExtractedSurface::basis(int e, const double* s, int order, PatchBasis& out) const {
  const int dc = surface_.dim;
  double ders[2][3 * (kMaxDegree + 1)];
  int nb[2] = {1, 1};
  double scale[2] = {1.0, 1.0};
  for (int a = 0; a < dc; ++a) {
    const double lo = surface_.element_lower(e, a), hi = surface_.element_upper(e, a);
    scale[a] = 1.0 / (hi - lo);
    bernsteinDerivatives(surface_.degrees[a], (s[a] - lo) * scale[a], order, ders[a]);
    nb[a] = surface_.degrees[a] + 1;
  }
  // Tensor Bernstein table (rows as rational_basis.h), derivatives with respect to s.
  const int rows = numDerivativeRows(dc, order);
  int orders[6][2] = {};
  for (int a = 0; a < dc && order >= 1; ++a) orders[1 + a][a] = 1;
  if (order >= 2) {
    for (int a = 0; a < dc; ++a)
      for (int b = a; b < dc; ++b) {
        orders[secondDerivativeRow(dc, a, b)][a] += 1;
        orders[secondDerivativeRow(dc, a, b)][b] += 1;
      }
  }
  Eigen::MatrixXd bern(rows, nb[0] * nb[1]);
  for (int j1 = 0; j1 < nb[1]; ++j1) {
    for (int j0 = 0; j0 < nb[0]; ++j0) {
      const int j[2] = {j0, j1};
      for (int r = 0; r < rows; ++r) {
        double v = 1.0;
        for (int a = 0; a < dc; ++a) {
          const int k = orders[r][a];
          v *= ders[a][k * nb[a] + j[a]] * (k == 0 ? 1.0 : k == 1 ? scale[a] : scale[a] * scale[a]);
        }
        bern(r, j0 + nb[0] * j1) = v;
      }
    }
  }
  const int f0 = surface_.function_offsets[e], f1 = surface_.function_offsets[e + 1];
  const Eigen::MatrixXd B = bern * surface_.extraction[e].transpose();
  Eigen::VectorXd w(f1 - f0);
  out.index.assign(surface_.functions.begin() + f0, surface_.functions.begin() + f1);
  for (int k = 0; k < w.size(); ++k) w(k) = weights_(out.index[k]);
  rationalize(B, w, dc, order, out.table);
}

PatchPoint ExtractedSurface::evaluate(int e, const double* s, int order) const {
  PatchBasis R;
  basis(e, s, order, R);
  const int dc = surface_.dim;
  Eigen::MatrixXd P(R.index.size(), points_.cols());
  for (int c = 0; c < P.rows(); ++c) P.row(c) = points_.row(R.index[c]);
  const Eigen::MatrixXd X = R.table * P;
  PatchPoint pt;
  pt.x = X.row(0).transpose();
  if (order >= 1) pt.dx = X.middleRows(1, dc).transpose();
  if (order >= 2) pt.ddx = X.middleRows(1 + dc, dc * (dc + 1) / 2).transpose();
  return pt;
}

}  // namespace ffriga
