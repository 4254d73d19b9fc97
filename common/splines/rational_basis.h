// Derivative bookkeeping for multivariate bases and the rational (NURBS) basis of
// paper Eq. (4): R_k = w_k B_k / W with W = sum_k w_k B_k.
//
// A basis table has one row per derivative and one column per function. Rows, for a
// parametric dimension d and derivative order <= 2:
//   row 0                 value
//   rows 1 .. d           d/dxi_a,               a = 0..d-1
//   rows d+1 ..           d^2/dxi_a dxi_b, a <= b, in the order (0,0),(0,1),..,(0,d-1),(1,1),..
#pragma once

#include <utility>

#include <Eigen/Dense>

namespace ffriga {

// Number of rows of a basis table for parametric dimension d and derivative order <= 2.
inline int numDerivativeRows(int d, int order) {
  return 1 + (order >= 1 ? d : 0) + (order >= 2 ? d * (d + 1) / 2 : 0);
}
// Row of d^2/dxi_a dxi_b (either order of a, b).
inline int secondDerivativeRow(int d, int a, int b) {
  if (a > b) std::swap(a, b);
  return 1 + d + a * d - a * (a - 1) / 2 + (b - a);
}

// Quotient rule for R_k = w_k B_k / W up to second derivatives:
//   R_a  = (w B_a - R W_a) / W
//   R_ab = (w B_ab - R_a W_b - R_b W_a - R W_ab) / W
// B: polynomial basis table (rows as above), w: weights (one per column). R gets B's shape.
void rationalize(const Eigen::MatrixXd& B, const Eigen::VectorXd& w, int d, int order,
                 Eigen::MatrixXd& R);

}  // namespace ffriga
