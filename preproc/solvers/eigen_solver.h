// Generalized symmetric eigenproblem K phi = lambda M phi (K symmetric, M symmetric positive
// definite, both as upper triangles) near a shift sigma, by ARPACK's implicitly restarted
// Lanczos method in shift-invert mode (dsaupd/dseupd, mode 3, bmat = 'G'):
//
//   OP = (K - sigma M)^{-1} M,  B = M,   nu = 1 / (lambda - sigma),
//
// with (K - sigma M) factorised once by CHOLMOD. Returns the `count` eigenvalues closest to
// sigma, ascending, with eigenvectors normalised to phi^T M phi = 1 (ARPACK manual,
// Lehoucq, Sorensen & Yang 1998, Sect. 3.2.3, "Shift-invert mode" for the generalized
// problem). lambda = omega^2 in (rad/s)^2 for K in N/m and M in kg.
#pragma once

#include <string>

#include <Eigen/Dense>

#include "preproc/solvers/sparse_matrix.h"

namespace ffriga {

struct EigenOptions {
  int count = 10;          // number of eigenpairs, 1 <= count < n
  double shift = 0.0;      // sigma, (rad/s)^2; K - sigma M must be positive definite
  double tolerance = 0.0;  // ARPACK relative tolerance; 0 means machine precision
  int max_iterations = 1000;
  std::string what = "eigenproblem";  // named in error messages
};

struct EigenResult {
  Eigen::VectorXd values;   // lambda, ascending
  Eigen::MatrixXd vectors;  // n x count, M-orthonormal
  int iterations = 0;
  int operator_applications = 0;
};

class SparseCholesky;

// Throws InputError if count is out of range, ComputeError if the factorisation or ARPACK
// fails (with ARPACK's info code translated).
EigenResult solveEigenproblem(const SparseMatrix& K, const SparseMatrix& M,
                              const EigenOptions& options);
// The same with K - sigma M already factorised (sigma = options.shift).
EigenResult solveEigenproblem(const SparseCholesky& shifted, const SparseMatrix& M,
                              const EigenOptions& options);

}  // namespace ffriga
