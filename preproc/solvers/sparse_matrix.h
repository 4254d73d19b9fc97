// The sparse matrices of igaprep (stiffness and mass, upper triangle stored: CHOLMOD's
// stype = 1) and their product with dense blocks.
//
//   symmetricProduct(upper, x) = A x  for the symmetric A whose upper triangle `upper` holds,
//
// over the columns of x in fixed blocks of 16 on the OpenMP threads: the same bits for any
// thread count (each block's sums run in one fixed order).
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>

namespace ffriga {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

Eigen::MatrixXd symmetricProduct(const SparseMatrix& upper, const Eigen::MatrixXd& x);

}  // namespace ffriga
