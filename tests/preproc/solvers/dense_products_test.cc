// The reduction's large products (preproc/solvers/dense_products.h: dgemm over fixed column
// blocks; preproc/solvers/sparse_matrix.h: symmetricProduct of an upper triangle), directly:
// the products against Eigen's within the standard rounding bound, empty shapes, and the same
// bits for any number of OpenMP threads.
#include "preproc/solvers/dense_products.h"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include <omp.h>
#include <catch2/catch.hpp>

#include "preproc/solvers/single_threaded_blas.h"
#include "preproc/solvers/sparse_matrix.h"

using namespace ffriga;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// Entries uniform in [-1, 1] from a generator of the test's own (the draws of other tests
// are left alone).
Eigen::MatrixXd randomMatrix(int rows, int cols, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) m(i) = u(gen);
  return m;
}

// Runs f with the given number of OpenMP threads (restored afterwards).
template <typename F>
auto withThreads(int threads, F f) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  auto result = f();
  omp_set_num_threads(before);
  return result;
}

}  // namespace

TEST_CASE("dense products: A^T B and A B within the rounding bound, any thread count same bits",
          "[products]") {
  // Rounding of an inner product of length k: |fl(x.y) - x.y| <= k eps |x|.|y| (Higham,
  // Accuracy and Stability, Sect. 3.1), whatever the order of the sums; the reference is
  // computed in long double, so its own error is negligible.
  const SingleThreadedBlas singleThreaded;  // each block one single-threaded dgemm, as used
  const int m = 37, k = 200, n = 150;       // 150 columns: blocks of 64, 64 and 22
  const Eigen::MatrixXd A = randomMatrix(k, m, 1), A2 = randomMatrix(m, k, 2);
  const Eigen::MatrixXd B = randomMatrix(k, n, 3);
  using MatrixL = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  const MatrixL exactT = A.cast<long double>().transpose() * B.cast<long double>();
  const MatrixL exact = A2.cast<long double>() * B.cast<long double>();
  const Eigen::MatrixXd boundT = k * kEps * (A.cwiseAbs().transpose() * B.cwiseAbs());
  const Eigen::MatrixXd bound = k * kEps * (A2.cwiseAbs() * B.cwiseAbs());
  const Eigen::MatrixXd CT = transposeTimes(A, B), C = times(A2, B);
  REQUIRE(CT.rows() == m);
  REQUIRE(CT.cols() == n);
  REQUIRE(C.rows() == m);
  REQUIRE(C.cols() == n);
  CHECK(((CT.cast<long double>() - exactT).cwiseAbs().cast<double>().array() <= boundT.array())
            .all());
  CHECK(((C.cast<long double>() - exact).cwiseAbs().cast<double>().array() <= bound.array()).all());
  // A wrong block offset would show as an error of order |C| itself, far above the bound.
  CHECK(boundT.maxCoeff() < 1e-10);
  for (const int threads : {1, 2, 3, 5}) {
    INFO(threads << " threads");
    CHECK(withThreads(threads, [&] { return transposeTimes(A, B); }) == CT);
    CHECK(withThreads(threads, [&] { return times(A2, B); }) == C);
  }
}

TEST_CASE("dense products: empty shapes and mismatched dimensions", "[products]") {
  const Eigen::MatrixXd A0(0, 4), B0(0, 6);
  const Eigen::MatrixXd Z = transposeTimes(A0, B0);  // k = 0: the zero 4 x 6 matrix
  CHECK(Z.rows() == 4);
  CHECK(Z.cols() == 6);
  CHECK(Z.isZero(0.0));
  CHECK(times(Eigen::MatrixXd(3, 0), Eigen::MatrixXd(0, 2)).isZero(0.0));
  CHECK(times(Eigen::MatrixXd(0, 5), Eigen::MatrixXd::Ones(5, 2)).rows() == 0);
  CHECK(transposeTimes(Eigen::MatrixXd::Ones(5, 2), Eigen::MatrixXd(5, 0)).cols() == 0);
  CHECK_THROWS_AS(times(Eigen::MatrixXd::Ones(3, 4), Eigen::MatrixXd::Ones(5, 2)),
                  std::invalid_argument);
  CHECK_THROWS_AS(transposeTimes(Eigen::MatrixXd::Ones(3, 4), Eigen::MatrixXd::Ones(5, 2)),
                  std::invalid_argument);
}

TEST_CASE("symmetricProduct: the symmetric matrix of an upper triangle times x, same bits",
          "[products]") {
  // A random sparse symmetric matrix stored as its upper triangle; the product with 40
  // columns (blocks of 16, 16, 8) against the full matrix's, to the inner-product bound of the
  // row lengths (<= n), and the same bits on 1 to 4 threads.
  const int n = 300;
  const Eigen::MatrixXd R = randomMatrix(n, n, 4);
  Eigen::MatrixXd full = (R.array().abs() > 0.97).select(R, 0.0);
  full = (full + full.transpose()).eval();
  full.diagonal().setConstant(3.0);
  const SparseMatrix upper = full.triangularView<Eigen::Upper>().toDenseMatrix().sparseView();
  const Eigen::MatrixXd x = randomMatrix(n, 40, 5);
  const Eigen::MatrixXd y = symmetricProduct(upper, x);
  const Eigen::MatrixXd bound = n * kEps * (full.cwiseAbs() * x.cwiseAbs());
  CHECK(((y - full * x).cwiseAbs().array() <= bound.array()).all());
  CHECK((y - full * x).cwiseAbs().maxCoeff() < 1e-12);  // ~20 terms of size 1 per row
  // The lower triangle is read from the upper: dropping a mirrored entry changes the result.
  CHECK((y - Eigen::MatrixXd(full.triangularView<Eigen::Upper>()) * x).norm() > 1.0);
  for (const int threads : {1, 2, 4}) {
    INFO(threads << " threads");
    CHECK(withThreads(threads, [&] { return symmetricProduct(upper, x); }) == y);
  }
}
