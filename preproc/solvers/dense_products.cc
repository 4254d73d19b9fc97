#include "preproc/solvers/dense_products.h"

#include <algorithm>
#include <cstddef>

#include "common/base/error.h"

extern "C" {
// BLAS level 3 (Fortran interface; hidden string lengths last, gfortran convention).
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
            const double* alpha, const double* a, const int* lda, const double* b, const int* ldb,
            const double* beta, double* c, const int* ldc, std::size_t transa_len,
            std::size_t transb_len);
}

namespace ffriga {

namespace {

Eigen::MatrixXd gemm(bool transposeA, const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  const int m = static_cast<int>(transposeA ? A.cols() : A.rows());
  const int k = static_cast<int>(transposeA ? A.rows() : A.cols());
  const int n = static_cast<int>(B.cols());
  FFRIGA_CHECK(B.rows() == k, "inner dimensions " << k << " and " << B.rows());
  Eigen::MatrixXd C(m, n);
  if (m == 0 || n == 0) return C;
  if (k == 0) return Eigen::MatrixXd::Zero(m, n);
  const double one = 1.0, zero = 0.0;
  const int lda = static_cast<int>(std::max<Eigen::Index>(1, A.rows()));
  const int ldb = static_cast<int>(std::max<Eigen::Index>(1, B.rows()));
  // Column blocks of a fixed width, one dgemm each, shared between the OpenMP threads: a
  // column of C is computed the same way whatever the number of threads.
  const int width = 64;
  const int blocks = (n + width - 1) / width;
#pragma omp parallel for schedule(dynamic, 1)
  for (int b = 0; b < blocks; ++b) {
    const int j = b * width;
    const int nb = std::min(width, n - j);
    dgemm_(transposeA ? "T" : "N", "N", &m, &nb, &k, &one, A.data(), &lda,
           B.data() + static_cast<std::size_t>(j) * ldb, &ldb, &zero,
           C.data() + static_cast<std::size_t>(j) * m, &m, 1, 1);
  }
  return C;
}

}  // namespace

Eigen::MatrixXd transposeTimes(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  return gemm(true, A, B);
}

Eigen::MatrixXd times(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  return gemm(false, A, B);
}

}  // namespace ffriga
