// The narrow interface around CHOLMOD (preproc/solvers/sparse_cholesky.h), directly: solves
// against Eigen's dense Cholesky within the condition number's bound, the right-hand-side
// paths that must give the same bits, a matrix that is not positive definite, the reuse of the
// symbolic analysis, the condition estimate and concurrent solves from OpenMP threads.
#include "preproc/solvers/sparse_cholesky.h"

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <omp.h>
#include <catch2/catch.hpp>

using namespace ffriga;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// Upper triangle (compressed, as SparseCholesky expects) of the 5-point Laplacian on an N x N
// grid (Dirichlet), 4 on the diagonal, plus shift * E; `diagonal` overrides entry (k, k).
SparseMatrix laplacian2d(int N, double shift, int k = -1, double diagonal = 0.0) {
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < N; ++j) {
    for (int i = 0; i < N; ++i) {
      const int r = i + N * j;
      t.emplace_back(r, r, r == k ? diagonal : 4.0 + shift);
      if (i + 1 < N) t.emplace_back(r, r + 1, -1.0);
      if (j + 1 < N) t.emplace_back(r, r + N, -1.0);
    }
  }
  SparseMatrix A(N * N, N * N);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

// Its condition number: eigenvalues 4 + shift - 2 cos(i pi / (N + 1)) - 2 cos(j pi / (N + 1)).
double laplacian2dCondition(int N, double shift) {
  const double c = std::cos(M_PI / (N + 1));
  return (4.0 + 4.0 * c + shift) / (4.0 - 4.0 * c + shift);
}

// The 7-point Laplacian on an N^3 grid plus 0.5 E (upper triangle), with `extra` long-range
// couplings -0.1 between rows 7 e and n - 1 - 5 e (still diagonally dominant, so SPD). Its fill
// makes CHOLMOD choose a supernodal factor (flops per entry of L > 40 for N = 12).
SparseMatrix laplacian3d(int N, int extra = 0) {
  std::vector<Eigen::Triplet<double>> t;
  const int n = N * N * N;
  for (int l = 0; l < N; ++l) {
    for (int j = 0; j < N; ++j) {
      for (int i = 0; i < N; ++i) {
        const int r = i + N * (j + N * l);
        t.emplace_back(r, r, 6.5);
        if (i + 1 < N) t.emplace_back(r, r + 1, -1.0);
        if (j + 1 < N) t.emplace_back(r, r + N, -1.0);
        if (l + 1 < N) t.emplace_back(r, r + N * N, -1.0);
      }
    }
  }
  for (int e = 0; e < extra; ++e) t.emplace_back(7 * e, n - 1 - 5 * e, -0.1);
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

// The full symmetric matrix of an upper triangle.
Eigen::MatrixXd fullMatrix(const SparseMatrix& upper) {
  const Eigen::MatrixXd U(upper);
  Eigen::MatrixXd A = U + U.transpose();
  A.diagonal() = U.diagonal();
  return A;
}

// Largest relative residual over the columns, |A x - b|_inf / (|A|_inf |x|_inf + |b|_inf).
double relativeResidual(const SparseMatrix& upper, const Eigen::MatrixXd& X,
                        const Eigen::MatrixXd& B) {
  const Eigen::MatrixXd A = fullMatrix(upper);
  const double normA = A.cwiseAbs().rowwise().sum().maxCoeff();
  double worst = 0.0;
  for (int j = 0; j < X.cols(); ++j) {
    const double r = (A * X.col(j) - B.col(j)).lpNorm<Eigen::Infinity>();
    worst = std::max(worst, r / (normA * X.col(j).lpNorm<Eigen::Infinity>() +
                                 B.col(j).lpNorm<Eigen::Infinity>()));
  }
  return worst;
}

// Entries uniform in [-1, 1] from a generator of the test's own (the draws of other tests
// are left alone).
Eigen::MatrixXd randomMatrix(int rows, int cols, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) m(i) = u(gen);
  return m;
}

}  // namespace

TEST_CASE("sparse Cholesky: solves agree with Eigen's dense LLT within the condition bound",
          "[cholesky]") {
  const int N = 30, n = N * N;
  const double shift = 0.01;
  const SparseMatrix A = laplacian2d(N, shift);
  SparseCholesky chol;
  std::string message;
  REQUIRE(chol.factorize(A, &message) == SparseCholesky::Status::kOk);
  REQUIRE(chol.size() == n);
  CHECK(chol.factorNonzeros() >= A.nonZeros());  // L holds at least A's pattern
  CHECK(chol.factorFlops() > 0.0);
  const Eigen::MatrixXd B = randomMatrix(n, 5, 1);
  const Eigen::MatrixXd X = chol.solve(B);
  const Eigen::MatrixXd Xd = fullMatrix(A).llt().solve(B);
  const double kappa = laplacian2dCondition(N, shift);  // ~260
  const double diff = (X - Xd).cwiseAbs().maxCoeff() / Xd.cwiseAbs().maxCoeff();
  INFO("condition " << kappa << ", relative difference " << diff << ", residual "
                    << relativeResidual(A, X, B));
  // Both solves are backward stable (the residual below: a few eps); their forward errors
  // are at most kappa times that, so they differ by at most ~2 kappa * (a few eps).
  CHECK(diff < 10.0 * kappa * kEps);
  CHECK(relativeResidual(A, X, B) < 10.0 * kEps);  // backward stable, independent of kappa
  // The condition estimate (min/max pivot of L L^T): every pivot lies between the smallest and
  // the largest eigenvalue, so 1/kappa <= rcond <= 1.
  CHECK(chol.rcond() >= 1.0 / kappa);
  CHECK(chol.rcond() <= 1.0);
}

TEST_CASE("sparse Cholesky: rcond of a diagonal matrix is its min/max ratio", "[cholesky]") {
  // L = diag(sqrt(d)), so (min L_ii / max L_ii)^2 = min d / max d, to a few ulps.
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < 50; ++k) t.emplace_back(k, k, 1.0 + 0.37 * k * k);
  SparseMatrix D(50, 50);
  D.setFromTriplets(t.begin(), t.end());
  D.makeCompressed();
  SparseCholesky chol;
  CHECK(chol.rcond() == 0.0);  // not factorised
  REQUIRE(chol.factorize(D, nullptr) == SparseCholesky::Status::kOk);
  CHECK(chol.rcond() == Approx(1.0 / (1.0 + 0.37 * 49 * 49)).epsilon(1e-14));
}

TEST_CASE("sparse Cholesky: dense, sparse and single right-hand sides give the same bits",
          "[cholesky]") {
  // Supernodal (3D grid) and simplicial (2D grid) factors. The same numbers through the dense,
  // the sparse and the single-vector paths must give the same bits where the work is the same:
  // a sparse B is made dense block by block, a one-column block is the single-vector solve,
  // and each block of 64 columns is solved on its own. A column solved alone and the same
  // column inside a wider block need not share bits (CHOLMOD works on groups of columns), so
  // there only round-off agreement is asked.
  for (const bool supernodal : {false, true}) {
    const SparseMatrix A = supernodal ? laplacian3d(12) : laplacian2d(30, 0.01);
    const int n = static_cast<int>(A.rows());
    SparseCholesky chol;
    REQUIRE(chol.factorize(A, nullptr) == SparseCholesky::Status::kOk);
    INFO((supernodal ? "3D grid" : "2D grid")
         << ", flops per entry of L " << chol.factorFlops() / chol.factorNonzeros());
    // A sparse B with 150 columns (three blocks: 64, 64, 22), about 2 % filled.
    const Eigen::MatrixXd R = randomMatrix(n, 150, 2);
    Eigen::MatrixXd B = (R.array().abs() > 0.98).select(R, 0.0);
    B.col(7).setZero();  // an empty column too
    SparseMatrix Bs = B.sparseView();
    Bs.makeCompressed();
    const Eigen::MatrixXd Xd = chol.solve(B), Xs = chol.solve(Bs);
    CHECK(Xd == Xs);
    CHECK(Xd.col(7).isZero(0.0));
    // Each block on its own: the same bits as inside the 150-column solve.
    CHECK(chol.solve(Eigen::MatrixXd(B.middleCols(64, 64))) == Xd.middleCols(64, 64));
    CHECK(chol.solve(Eigen::MatrixXd(B.rightCols(22))) == Xd.rightCols(22));
    // Single vectors: bit for bit a one-column matrix; to round-off a column of a block.
    Eigen::VectorXd x(n);
    double worst = 0.0;
    for (const int j : {0, 5, 63, 64, 100, 149}) {
      chol.solve(B.col(j).data(), x.data());
      CHECK(chol.solve(Eigen::MatrixXd(B.col(j))) == x);
      worst = std::max(worst, (x - Xd.col(j)).cwiseAbs().maxCoeff() / x.cwiseAbs().maxCoeff());
    }
    // Two backward-stable solves of condition ~30 (2D: ~260): within ~2 kappa eps of each
    // other; 1e-12 bounds both.
    CHECK(worst < 1e-12);
    CHECK(relativeResidual(A, Xd.leftCols(10), B.leftCols(10)) < 10.0 * kEps);
  }
}

TEST_CASE("sparse Cholesky: a matrix that is not positive definite is reported", "[cholesky]") {
  // The Laplacian with a single negative diagonal entry at column k: every principal
  // submatrix without k is positive definite and the pivot of k is at most -1, so the
  // factorisation breaks down exactly where it reaches column k, whatever the ordering.
  const int N = 10, n = N * N;
  for (const int k : {0, 53, n - 1}) {
    SparseCholesky chol;
    std::string message;
    CHECK(chol.factorize(laplacian2d(N, 0.01, k, -1.0), &message) ==
          SparseCholesky::Status::kNotPositiveDefinite);
    INFO("message: " << message);
    CHECK(message.find("not positive definite") != std::string::npos);
    CHECK(message.find(" of " + std::to_string(n)) != std::string::npos);
    CHECK(chol.rcond() == 0.0);
    CHECK_THROWS(
        chol.solve(Eigen::MatrixXd(Eigen::MatrixXd::Ones(n, 1))));  // no factor to solve with
    // The same object then factorises a positive definite matrix of that pattern.
    REQUIRE(chol.factorize(laplacian2d(N, 0.01), &message) == SparseCholesky::Status::kOk);
    const Eigen::MatrixXd b = Eigen::MatrixXd::Ones(n, 1);
    CHECK(relativeResidual(laplacian2d(N, 0.01), chol.solve(b), b) < 10.0 * kEps);
  }
}

TEST_CASE("sparse Cholesky: the failure message names the matrix's failing column",
          "[cholesky]") {
  // The column in the message is the matrix's, not CHOLMOD's L->minor (a position in the
  // fill-reducing order: once "column 68 of 100" for k = 0). By the construction above the
  // failing column is k.
  const int N = 10, n = N * N;
  for (const int k : {0, 53, n - 1}) {
    SparseCholesky chol;
    std::string message;
    REQUIRE(chol.factorize(laplacian2d(N, 0.01, k, -1.0), &message) ==
            SparseCholesky::Status::kNotPositiveDefinite);
    INFO("message: " << message);
    CHECK(message.find("column " + std::to_string(k) + " of " + std::to_string(n)) !=
          std::string::npos);
  }
}

TEST_CASE("sparse Cholesky: the analysis is reused for matrices of the same pattern",
          "[cholesky]") {
  // K - sigma M for several sigma: one analysis, several factorisations, each the same bits as
  // a fresh object's (the ordering is a function of the pattern alone).
  const int N = 30;
  SparseCholesky chol;
  std::string message;
  REQUIRE(chol.analyze(laplacian2d(N, 0.01), &message) == SparseCholesky::Status::kOk);
  const double nnz = chol.factorNonzeros(), flops = chol.factorFlops();
  CHECK(chol.rcond() == 0.0);  // analysed, not factorised
  REQUIRE(chol.analyze(laplacian2d(N, 0.01), &message) == SparseCholesky::Status::kOk);
  CHECK(chol.factorNonzeros() == nnz);
  CHECK(chol.factorFlops() == flops);
  const Eigen::MatrixXd B = randomMatrix(N * N, 3, 3);
  for (const double shift : {0.01, 1.0, 100.0}) {
    const SparseMatrix A = laplacian2d(N, shift);
    REQUIRE(chol.factorize(A, &message) == SparseCholesky::Status::kOk);
    SparseCholesky fresh;
    REQUIRE(fresh.factorize(A, &message) == SparseCholesky::Status::kOk);
    CHECK(chol.solve(B) == fresh.solve(B));
    CHECK(chol.rcond() == fresh.rcond());
    CHECK(chol.factorNonzeros() == nnz);
  }
}

TEST_CASE("sparse Cholesky: a new pattern of the same size is analysed again",
          "[cholesky]") {
  // analyze() once compared the size only, so factorize() of a matrix with entries outside
  // the analysed pattern kept the old ordering and supernodes: CHOLMOD dropped the new
  // entries and returned a wrong factor with status kOk (measured: relative residual 4e-3
  // instead of 4e-16; the counts stayed those of the old pattern).
  const SparseMatrix A0 = laplacian3d(12), A1 = laplacian3d(12, 30);
  SparseCholesky reused, fresh;
  std::string message;
  REQUIRE(reused.factorize(A0, &message) == SparseCholesky::Status::kOk);
  REQUIRE(reused.factorize(A1, &message) == SparseCholesky::Status::kOk);
  REQUIRE(fresh.factorize(A1, &message) == SparseCholesky::Status::kOk);
  CHECK(reused.factorNonzeros() == fresh.factorNonzeros());
  const Eigen::MatrixXd b = randomMatrix(static_cast<int>(A1.rows()), 1, 4);
  const double residual = relativeResidual(A1, reused.solve(b), b);
  INFO("residual of the reused analysis " << residual);
  CHECK(residual < 10.0 * kEps);  // as a fresh factor's (backward stable)
}

TEST_CASE("sparse Cholesky: concurrent solves on OpenMP threads give the serial bits",
          "[cholesky]") {
  // One factorisation, solves from 4 threads at once (single vectors and blocks, several
  // rounds so that they overlap): every result equal bit for bit to the serial solve.
  const SparseMatrix A = laplacian3d(12);
  const int n = static_cast<int>(A.rows());
  SparseCholesky chol;
  REQUIRE(chol.factorize(A, nullptr) == SparseCholesky::Status::kOk);
  const int jobs = 32;
  const Eigen::MatrixXd B = randomMatrix(n, jobs, 5);
  std::vector<Eigen::VectorXd> serial(jobs, Eigen::VectorXd(n)), parallel = serial;
  for (int j = 0; j < jobs; ++j) chol.solve(B.col(j).data(), serial[j].data());
  const Eigen::MatrixXd blockSerial = chol.solve(B);
  std::vector<Eigen::MatrixXd> blockParallel(4);
  int threads = 0;
#pragma omp parallel num_threads(4)
  {
#pragma omp single
    threads = omp_get_num_threads();
#pragma omp for schedule(dynamic, 1)
    for (int j = 0; j < jobs + 4; ++j) {
      if (j < jobs)
        chol.solve(B.col(j).data(), parallel[j].data());
      else
        blockParallel[j - jobs] = chol.solve(B);
    }
  }
  CHECK(threads == 4);
  for (int j = 0; j < jobs; ++j) CHECK(parallel[j] == serial[j]);
  for (const Eigen::MatrixXd& X : blockParallel) CHECK(X == blockSerial);
}
