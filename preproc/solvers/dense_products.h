// Large dense products of the reduction (Psi^T (M Psi), Psi T, Phi_c^T (Ms Phi_d)) through
// the BLAS routine dgemm, so that an optimised BLAS (OpenBLAS, see .ci/install-deps) does the
// O(n nq^2) work: with nq ~ 1400 elastic coordinates on 140k DOFs each product is ~5e11
// flops. The columns of the result are split into fixed-width blocks over the OpenMP
// threads, each a single-threaded dgemm (preproc/solvers/single_threaded_blas.h): the same bits for
// any thread count.
//
//   transposeTimes(A, B) = A^T B,   times(A, B) = A B.
#pragma once

#include <Eigen/Dense>

namespace ffriga {

Eigen::MatrixXd transposeTimes(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B);
Eigen::MatrixXd times(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B);

}  // namespace ffriga
