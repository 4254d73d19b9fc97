#include "preproc/solvers/sparse_cholesky.h"

#include <algorithm>
#include <cstring>
#include <type_traits>

#include <cholmod.h>

#include "common/base/error.h"

namespace ffriga {

namespace {

// A cholmod_sparse view of an Eigen matrix (no copy; CHOLMOD does not modify it).
cholmod_sparse view(const SparseMatrix& A) {
  cholmod_sparse s;
  std::memset(&s, 0, sizeof(s));
  s.nrow = static_cast<std::size_t>(A.rows());
  s.ncol = static_cast<std::size_t>(A.cols());
  s.nzmax = static_cast<std::size_t>(A.nonZeros());
  s.p = const_cast<int*>(A.outerIndexPtr());
  s.i = const_cast<int*>(A.innerIndexPtr());
  s.x = const_cast<double*>(A.valuePtr());
  s.stype = 1;  // upper triangle holds the matrix
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

cholmod_dense denseView(const double* x, int rows, int cols) {
  cholmod_dense d;
  std::memset(&d, 0, sizeof(d));
  d.nrow = static_cast<std::size_t>(rows);
  d.ncol = static_cast<std::size_t>(cols);
  d.nzmax = d.nrow * d.ncol;
  d.d = d.nrow;
  d.x = const_cast<double*>(x);
  d.xtype = CHOLMOD_REAL;
  d.dtype = CHOLMOD_DOUBLE;
  return d;
}

// Errors reported by CHOLMOD's handler go here (one common object per wrapper).
thread_local std::string lastCholmodError;

void errorHandler(int status, const char* file, int line, const char* message) {
  lastCholmodError = Str() << "CHOLMOD status " << status << " (" << (message ? message : "")
                           << ") at " << (file ? file : "?") << ":" << line;
}

// cholmod_start with CHOLMOD's printing silenced and its errors routed to errorHandler.
void startQuietly(cholmod_common* common) {
  cholmod_start(common);
  common->print = 0;
  common->error_handler = errorHandler;
}

SparseCholesky::Status translate(int status, std::string* message, const char* stage) {
  if (status == CHOLMOD_OK) return SparseCholesky::Status::kOk;
  if (message) *message = Str() << stage << ": " << lastCholmodError;
  if (status == CHOLMOD_OUT_OF_MEMORY) return SparseCholesky::Status::kOutOfMemory;
  return SparseCholesky::Status::kFailed;
}

}  // namespace

SparseCholesky::SparseCholesky() {
  common_ = new cholmod_common;
  startQuietly(common_);
  common_->final_ll = 1;
}

SparseCholesky::~SparseCholesky() {
  if (factor_) cholmod_free_factor(&factor_, common_);
  cholmod_finish(common_);
  delete common_;
}

namespace {

// FNV-1a (one index per step instead of one byte: a pass at memory speed) over the column
// starts and row indices of a compressed matrix: two patterns of one size and nonzero
// count that hash alike are taken as the same.
unsigned long long patternHash(const SparseMatrix& A) {
  unsigned long long h = 14695981039346656037ull;
  auto mix = [&h](const auto* index, long count) {
    for (long i = 0; i < count; ++i)
      h = (h ^ static_cast<unsigned long long>(index[i])) * 1099511628211ull;
  };
  mix(A.outerIndexPtr(), A.outerSize() + 1);
  mix(A.innerIndexPtr(), A.nonZeros());
  return h;
}

}  // namespace

SparseCholesky::Status SparseCholesky::analyze(const SparseMatrix& upper, std::string* message) {
  FFRIGA_CHECK(upper.rows() == upper.cols() && upper.isCompressed(),
               "matrix " << upper.rows() << "x" << upper.cols());
  const unsigned long long pattern = patternHash(upper);
  if (factor_ && n_ == upper.rows() && nonzeros_ == upper.nonZeros() && pattern_ == pattern)
    return Status::kOk;
  if (factor_) cholmod_free_factor(&factor_, common_);
  cholmod_sparse A = view(upper);
  lastCholmodError.clear();
  factor_ = cholmod_analyze(&A, common_);
  n_ = static_cast<int>(upper.rows());
  nonzeros_ = upper.nonZeros();
  pattern_ = pattern;
  factorized_ = false;
  factor_flops_ = common_->fl;
  if (!factor_) {
    if (message) *message = "symbolic analysis failed: " + lastCholmodError;
    return common_->status == CHOLMOD_OUT_OF_MEMORY ? Status::kOutOfMemory : Status::kFailed;
  }
  // A supernodal factor stores its supernodes' dense blocks (xsize, known after the
  // analysis), more than the fundamental count lnz.
  factor_nonzeros_ = factor_->is_super ? static_cast<double>(factor_->xsize) : common_->lnz;
  return translate(common_->status, message, "symbolic analysis");
}

SparseCholesky::Status SparseCholesky::factorize(const SparseMatrix& upper, std::string* message) {
  const Status a = analyze(upper, message);
  if (a != Status::kOk) return a;
  cholmod_sparse A = view(upper);
  lastCholmodError.clear();
  const int ok = cholmod_factorize(&A, factor_, common_);
  factorized_ = false;
  if (common_->status == CHOLMOD_NOT_POSDEF) {
    if (message) {
      // L->minor counts in the fill-reducing order P A P^T; Perm[k] is the matrix's column
      // eliminated k-th.
      const long k = static_cast<long>(factor_->minor);
      const int* perm = static_cast<const int*>(factor_->Perm);
      const long column = perm && k < n_ ? perm[k] : k;
      *message = Str() << "the matrix is not positive definite (the factorisation breaks down "
                       << "at column " << column << " of " << n_ << ")";
    }
    return Status::kNotPositiveDefinite;
  }
  if (!ok || common_->status != CHOLMOD_OK)
    return translate(common_->status, message, "factorisation");
  factorized_ = true;
  return Status::kOk;
}

double SparseCholesky::rcond() const {
  return factorized_ ? cholmod_rcond(factor_, common_) : 0.0;
}

namespace {

// A CHOLMOD workspace for one solve call (the factor's own common object is not shared
// between threads).
class SolveWorkspace {
 public:
  SolveWorkspace() { startQuietly(&common_); }
  ~SolveWorkspace() { cholmod_finish(&common_); }
  SolveWorkspace(const SolveWorkspace&) = delete;
  SolveWorkspace& operator=(const SolveWorkspace&) = delete;
  // X = A^{-1} B into x (rows x cols, column-major).
  void solve(cholmod_factor* factor, const double* b, int rows, int cols, double* x) {
    cholmod_dense B = denseView(b, rows, cols);
    cholmod_dense* X = cholmod_solve(CHOLMOD_A, factor, &B, &common_);
    if (!X) throw ComputeError("CHOLMOD solve failed: " + lastCholmodError);
    std::memcpy(x, X->x, sizeof(double) * static_cast<std::size_t>(rows) * cols);
    cholmod_free_dense(&X, &common_);
  }

 private:
  cholmod_common common_;
};

constexpr int kSolveBlock = 64;  // columns per CHOLMOD call: bounds CHOLMOD's workspace

}  // namespace

void SparseCholesky::solve(const double* b, double* x) const {
  FFRIGA_CHECK(factorized_, "solve before a successful factorisation");
  SolveWorkspace().solve(factor_, b, n_, 1, x);
}

namespace {

// X = A^{-1} B in blocks of kSolveBlock columns: a dense B is read in place, a sparse one
// made dense one block at a time.
template <typename Rhs>
Eigen::MatrixXd solveInBlocks(cholmod_factor* factor, int n, const Rhs& B) {
  Eigen::MatrixXd X(B.rows(), B.cols()), block;
  SolveWorkspace w;
  for (Eigen::Index j = 0; j < B.cols(); j += kSolveBlock) {
    const int nc = static_cast<int>(std::min<Eigen::Index>(kSolveBlock, B.cols() - j));
    const double* b;
    if constexpr (std::is_same_v<Rhs, Eigen::MatrixXd>) {
      b = B.data() + j * B.rows();
    } else {
      block = B.middleCols(j, nc);
      b = block.data();
    }
    w.solve(factor, b, n, nc, X.data() + j * B.rows());
  }
  return X;
}

}  // namespace

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) const {
  FFRIGA_CHECK(factorized_, "solve before a successful factorisation");
  FFRIGA_CHECK(B.rows() == n_, "right-hand side has " << B.rows() << " rows, expected " << n_);
  return solveInBlocks(factor_, n_, B);
}

Eigen::MatrixXd SparseCholesky::solve(const SparseMatrix& B) const {
  FFRIGA_CHECK(factorized_, "solve before a successful factorisation");
  FFRIGA_CHECK(B.rows() == n_, "right-hand side has " << B.rows() << " rows, expected " << n_);
  return solveInBlocks(factor_, n_, B);
}

}  // namespace ffriga
