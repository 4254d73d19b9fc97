#include "common/splines/rational_basis.h"

#include <algorithm>

#include "common/base/error.h"

namespace ffriga {

void rationalize(const Eigen::MatrixXd& B, const Eigen::VectorXd& w, int d, int order,
                 Eigen::MatrixXd& R) {
  const int rows = numDerivativeRows(d, order);
  FFRIGA_ASSERT(B.rows() >= rows && B.cols() == w.size(),
                "basis table " << B.rows() << "x" << B.cols());
  // Weighted polynomial basis and the weight function W with its derivatives.
  // Per-thread workspaces, one per order: evaluated in the contact search's OpenMP loop,
  // where the orders alternate (Newton 2, line search 0) and Eigen reuses storage only for
  // the same size.
  thread_local Eigen::MatrixXd BwOf[3];
  thread_local Eigen::VectorXd WOf[3];
  Eigen::MatrixXd& Bw = BwOf[std::min(order, 2)];
  Eigen::VectorXd& W = WOf[std::min(order, 2)];
  Bw.noalias() = B.topRows(rows) * w.asDiagonal();
  W.noalias() = Bw.rowwise().sum();
  R.resize(rows, B.cols());
  const double invW = 1.0 / W(0);
  R.row(0) = Bw.row(0) * invW;
  if (order >= 1) {
    for (int a = 0; a < d; ++a) R.row(1 + a) = (Bw.row(1 + a) - R.row(0) * W(1 + a)) * invW;
  }
  if (order >= 2) {
    for (int a = 0; a < d; ++a) {
      for (int b = a; b < d; ++b) {
        const int ab = secondDerivativeRow(d, a, b);
        R.row(ab) =
            (Bw.row(ab) - R.row(1 + a) * W(1 + b) - R.row(1 + b) * W(1 + a) - R.row(0) * W(ab)) *
            invW;
      }
    }
  }
}

}  // namespace ffriga
