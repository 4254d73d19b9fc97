// Test fixtures: ContactSurface data (common/sid/sid.h) built from a tensor NURBS patch by Bezier
// extraction. Every interior break is inserted up to multiplicity p (knotInsertionMatrix,
// N_i = sum_j T(j, i) Nbar_j); on element e the fine functions e*p .. e*p+p are the
// Bernstein polynomials, so C_e(k, b) = T(e*p + b, k). Function numbers are the patch's
// control point numbers.
#pragma once

#include <cmath>
#include <vector>

#include "common/splines/nurbs_patch.h"
#include "common/splines/refinement.h"
#include "common/sid/sid.h"

namespace ffriga::test {

inline ContactSurface bezierExtract(const NurbsPatch& patch, double outward_sign = 1.0) {
  const int d = patch.paramDim();
  ContactSurface s;
  s.name = "contact";
  s.dim = d;
  s.outward_sign = outward_sign;
  std::vector<Eigen::MatrixXd> T(d);
  std::vector<std::vector<double>> breaks(d);
  for (int a = 0; a < d; ++a) {
    const KnotVector& U = patch.knots(a);
    const int p = U.degree();
    s.degrees.push_back(p);
    breaks[a] = U.breaks();
    std::vector<double> X;
    for (std::size_t i = 1; i + 1 < breaks[a].size(); ++i)
      for (int m = U.multiplicity(breaks[a][i]); m < p; ++m) X.push_back(breaks[a][i]);
    KnotVector fine;
    T[a] = X.empty() ? Eigen::MatrixXd::Identity(U.numBasis(), U.numBasis())
                     : knotInsertionMatrix(U, X, &fine);
  }
  const int ne0 = static_cast<int>(breaks[0].size()) - 1;
  const int ne1 = d == 2 ? static_cast<int>(breaks[1].size()) - 1 : 1;
  s.element_lower.resize(ne0 * ne1, d);
  s.element_upper.resize(ne0 * ne1, d);
  s.function_offsets.push_back(0);
  const int p0 = s.degrees[0], p1 = d == 2 ? s.degrees[1] : 0;
  for (int e1 = 0; e1 < ne1; ++e1) {
    for (int e0 = 0; e0 < ne0; ++e0) {
      const int e = e0 + ne0 * e1;
      s.element_lower(e, 0) = breaks[0][e0];
      s.element_upper(e, 0) = breaks[0][e0 + 1];
      if (d == 2) {
        s.element_lower(e, 1) = breaks[1][e1];
        s.element_upper(e, 1) = breaks[1][e1 + 1];
      }
      s.element_level.push_back(0);
      std::vector<int> active;
      std::vector<Eigen::VectorXd> rows;
      for (int k = 0; k < patch.numControlPoints(); ++k) {
        const std::array<int, 3> ti = patch.tensorIndex(k);
        Eigen::VectorXd row((p0 + 1) * (p1 + 1));
        for (int b1 = 0; b1 <= p1; ++b1)
          for (int b0 = 0; b0 <= p0; ++b0)
            row(b0 + (p0 + 1) * b1) =
                T[0](e0 * p0 + b0, ti[0]) * (d == 2 ? T[1](e1 * p1 + b1, ti[1]) : 1.0);
        if (row.cwiseAbs().maxCoeff() > 0.0) {
          active.push_back(k);
          rows.push_back(row);
        }
      }
      Eigen::MatrixXd C(active.size(), (p0 + 1) * (p1 + 1));
      for (std::size_t i = 0; i < active.size(); ++i) C.row(i) = rows[i].transpose();
      s.functions.insert(s.functions.end(), active.begin(), active.end());
      s.function_offsets.push_back(static_cast<int>(s.functions.size()));
      s.extraction.push_back(C);
    }
  }
  return s;
}

}  // namespace ffriga::test

namespace ffriga::test {

// Collocation points at the tensor Greville abscissae of the patch, each with the same
// weight (m^2 or m): enough for tests of the contact kinematics.
inline void addGrevilleCollocation(const NurbsPatch& patch, ContactSurface& s, double weight) {
  const int d = patch.paramDim();
  const std::vector<double> g0 = patch.knots(0).greville();
  const std::vector<double> g1 = d == 2 ? patch.knots(1).greville() : std::vector<double>{0.0};
  const int n = static_cast<int>(g0.size() * g1.size());
  s.collocation_points.resize(n, d);
  s.collocation_element.clear();
  s.collocation_weights = Eigen::VectorXd::Constant(n, weight);
  int i = 0;
  for (double v : g1) {
    for (double u : g0) {
      s.collocation_points(i, 0) = u;
      if (d == 2) s.collocation_points(i, 1) = v;
      int e = 0;
      for (int k = 0; k < s.element_lower.rows(); ++k) {
        bool in = true;
        for (int a = 0; a < d; ++a)
          in = in && s.collocation_points(i, a) >= s.element_lower(k, a) &&
               s.collocation_points(i, a) <= s.element_upper(k, a);
        if (in) {
          e = k;
          break;
        }
      }
      s.collocation_element.push_back(e);
      ++i;
    }
  }
}

}  // namespace ffriga::test
