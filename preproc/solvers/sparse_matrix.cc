#include "preproc/solvers/sparse_matrix.h"

#include <algorithm>

namespace ffriga {

Eigen::MatrixXd symmetricProduct(const SparseMatrix& upper, const Eigen::MatrixXd& x) {
  constexpr int kWidth = 16;  // columns per block: fixed, so the bits are the same for any
                              // number of threads
  Eigen::MatrixXd y(upper.rows(), x.cols());
  const int blocks = static_cast<int>((x.cols() + kWidth - 1) / kWidth);
#pragma omp parallel for schedule(dynamic, 1)
  for (int b = 0; b < blocks; ++b) {
    const Eigen::Index j = static_cast<Eigen::Index>(kWidth) * b;
    const Eigen::Index nc = std::min<Eigen::Index>(kWidth, x.cols() - j);
    y.middleCols(j, nc) = upper.selfadjointView<Eigen::Upper>() * x.middleCols(j, nc);
  }
  return y;
}

}  // namespace ffriga
