// A narrow interface in front of CHOLMOD (SuiteSparse): sparse Cholesky factorisation
// A = L L^T (supernodal or simplicial, CHOLMOD's choice) of a symmetric positive definite
// matrix given by its upper triangle, with the fill-reducing ordering analysed once and
// reused for every matrix of the same pattern (K - sigma M for several sigma, K_ii), and
// solves with many right-hand sides at once. CHOLMOD's own printing is silenced; failures
// come back as a status and a message.
#pragma once

#include <string>

#include <Eigen/Dense>

#include "preproc/solvers/sparse_matrix.h"

struct cholmod_common_struct;
struct cholmod_factor_struct;

namespace ffriga {

class SparseCholesky {
 public:
  enum class Status { kOk, kNotPositiveDefinite, kOutOfMemory, kFailed };

  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // Symbolic analysis (ordering, elimination tree) of the pattern of `upper` (square,
  // compressed, upper triangle). Repeated calls with the same pattern (its size, nonzero
  // count and a 64-bit hash of its indices) keep the analysis; another pattern is analysed
  // anew.
  Status analyze(const SparseMatrix& upper, std::string* message);
  // Numeric factorisation of `upper` (analysed first if needed). kNotPositiveDefinite
  // names the failing column in the message.
  Status factorize(const SparseMatrix& upper, std::string* message);
  // Crude reciprocal condition estimate (min/max diagonal of L, squared), 0 if not factorised.
  double rcond() const;
  int size() const { return n_; }
  // From the symbolic analysis: stored entries of L and the floating-point operations of
  // one numeric factorisation (CHOLMOD's counts for the ordering it chose).
  double factorNonzeros() const { return factor_nonzeros_; }
  double factorFlops() const { return factor_flops_; }

  // X = A^{-1} B for any number of columns (solved in blocks to bound the workspace; a
  // sparse B is made dense one block at a time).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
  Eigen::MatrixXd solve(const SparseMatrix& B) const;
  // x = A^{-1} b for one vector of length size() (x may not alias b).
  void solve(const double* b, double* x) const;
  // The solves only read the factor and each call has its own CHOLMOD workspace: several
  // threads may solve with one factorisation at once.

 private:
  cholmod_common_struct* common_ = nullptr;
  cholmod_factor_struct* factor_ = nullptr;
  int n_ = 0;
  long nonzeros_ = 0;              // of the analysed pattern
  unsigned long long pattern_ = 0;  // hash of the analysed pattern's indices
  bool factorized_ = false;
  double factor_nonzeros_ = 0.0;
  double factor_flops_ = 0.0;
};

}  // namespace ffriga
