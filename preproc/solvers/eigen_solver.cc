#include "preproc/solvers/eigen_solver.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include "common/base/error.h"
#include "preproc/solvers/single_threaded_blas.h"
#include "preproc/solvers/sparse_cholesky.h"

extern "C" {
// ARPACK (Fortran 77); hidden string lengths follow gfortran's convention (size_t, last).
void dsaupd_(int* ido, const char* bmat, const int* n, const char* which, const int* nev,
             const double* tol, double* resid, const int* ncv, double* v, const int* ldv,
             int* iparam, int* ipntr, double* workd, double* workl, const int* lworkl, int* info,
             std::size_t bmat_len, std::size_t which_len);
void dseupd_(const int* rvec, const char* howmny, int* select, double* d, double* z, const int* ldz,
             const double* sigma, const char* bmat, const int* n, const char* which, const int* nev,
             const double* tol, double* resid, const int* ncv, double* v, const int* ldv,
             int* iparam, int* ipntr, double* workd, double* workl, const int* lworkl, int* info,
             std::size_t howmny_len, std::size_t bmat_len, std::size_t which_len);
}

namespace ffriga {

namespace {

// Meaning of dsaupd's info codes (ARPACK dsaupd.f documentation).
std::string dsaupdMessage(int info) {
  switch (info) {
    case 1:
      return "maximum number of iterations reached";
    case 3:
      return "no shifts could be applied during an implicit restart; increase ncv";
    case -1:
      return "n must be positive";
    case -2:
      return "nev must be positive";
    case -3:
      return "ncv must satisfy nev < ncv <= n";
    case -4:
      return "the maximum number of iterations must be positive";
    case -5:
      return "invalid 'which'";
    case -6:
      return "invalid 'bmat'";
    case -7:
      return "workl too small";
    case -8:
      return "error from the LAPACK tridiagonal eigenvalue routine";
    case -9:
      return "starting vector is zero";
    case -10:
      return "invalid mode";
    case -11:
      return "mode and bmat are incompatible";
    case -12:
      return "ishift must be 0 or 1";
    case -9999:
      return "could not build an Arnoldi factorisation (B may not be positive definite)";
    default:
      return Str() << "unknown ARPACK code " << info;
  }
}

std::string dseupdMessage(int info) {
  switch (info) {
    case -14:
      return "dsaupd did not find any eigenvalue to sufficient accuracy";
    case -15:
      return "howmny must be 'A' or 'S' with rvec";
    case -16:
      return "howmny = 'S' is not implemented";
    case -17:
      return "eigenvalue counts differ between dsaupd and dseupd";
    default:
      return dsaupdMessage(info);
  }
}


// ARPACK's own random start (info = 0) continues one LAPACK random stream through every call
// of the process, so a result would depend on what was solved before. A fixed start vector
// instead: components in [-1, 1) from SplitMix64 with a fixed seed (integer arithmetic, the
// same bits on every platform); ARPACK applies OP to it first (range of OP for bmat = 'G').
std::vector<double> startVector(int n) {
  std::vector<double> v(n);
  std::uint64_t state = 0x9E3779B97F4A7C15ULL;
  for (int i = 0; i < n; ++i) {
    state += 0x9E3779B97F4A7C15ULL;
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    v[i] = static_cast<double>(z >> 11) * 0x1.0p-52 - 1.0;  // 53 bits: [0, 2) - 1
  }
  return v;
}

// ARPACK's state for dsaupd/dseupd (mode 3, bmat = 'G', which = 'LM'): sizes and work arrays.
struct ArpackState {
  ArpackState(int size, const EigenOptions& o)
      : n(size),
        nev(o.count),
        ncv(std::min(n, std::max(2 * nev + 1, nev + 20))),
        lworkl(ncv * (ncv + 8)),
        resid(startVector(n)),
        v(static_cast<std::size_t>(n) * ncv),
        workd(3 * n),
        workl(lworkl) {
    iparam[0] = 1;  // exact shifts
    iparam[2] = o.max_iterations;
    iparam[6] = 3;  // shift-invert
  }
  const int n, nev, ncv, lworkl;
  std::vector<double> resid, v, workd, workl;
  int iparam[11] = {0}, ipntr[11] = {0};
  int ido = 0, info = 1;  // 1: start from resid
  const char bmat = 'G';
  const char which[3] = "LM";
};

// The Lanczos iterations (dsaupd's reverse communication): applies OP = (K - sigma M)^{-1} M
// and B = M until ARPACK has converged. Throws ComputeError if dsaupd fails.
void lanczosIterations(const SparseCholesky& chol, const SparseMatrix& M, const EigenOptions& o,
                       ArpackState& st, EigenResult& result) {
  const int n = st.n;
  std::vector<double> tmp(n);
  while (true) {
    dsaupd_(&st.ido, &st.bmat, &n, st.which, &st.nev, &o.tolerance, st.resid.data(), &st.ncv,
            st.v.data(), &n, st.iparam, st.ipntr, st.workd.data(), st.workl.data(), &st.lworkl,
            &st.info, 1, 2);
    double* x = st.workd.data() + st.ipntr[0] - 1;
    double* y = st.workd.data() + st.ipntr[1] - 1;
    if (st.ido == -1 || st.ido == 1) {
      // y = (K - sigma M)^{-1} M x; for ido = 1, M x is already at ipntr[2].
      Eigen::Map<Eigen::VectorXd> tv(tmp.data(), n);
      if (st.ido == 1) {
        tv = Eigen::Map<const Eigen::VectorXd>(st.workd.data() + st.ipntr[2] - 1, n);
      } else {
        tv = M.selfadjointView<Eigen::Upper>() * Eigen::Map<const Eigen::VectorXd>(x, n);
      }
      chol.solve(tmp.data(), y);
      ++result.operator_applications;
    } else if (st.ido == 2) {
      Eigen::Map<Eigen::VectorXd>(y, n) =
          M.selfadjointView<Eigen::Upper>() * Eigen::Map<const Eigen::VectorXd>(x, n);
    } else {
      break;
    }
  }
  if (st.info != 0) {
    throw ComputeError(Str() << o.what << ": ARPACK dsaupd failed (info = " << st.info << "): "
                             << dsaupdMessage(st.info) << "; " << st.iparam[4] << " of " << st.nev
                             << " eigenvalues converged after " << st.iparam[2] << " iterations");
  }
}

// The Ritz pairs (dseupd): eigenvalues d and eigenvectors Z (n x nev), in ARPACK's order.
// Throws ComputeError if dseupd fails or fewer than nev eigenvalues converged.
void ritzPairs(const EigenOptions& o, ArpackState& st, std::vector<double>& d, Eigen::MatrixXd& Z) {
  const int n = st.n;
  const int rvec = 1;
  const char howmny = 'A';
  std::vector<int> select(st.ncv, 0);
  dseupd_(&rvec, &howmny, select.data(), d.data(), Z.data(), &n, &o.shift, &st.bmat, &n, st.which,
          &st.nev, &o.tolerance, st.resid.data(), &st.ncv, st.v.data(), &n, st.iparam, st.ipntr,
          st.workd.data(), st.workl.data(), &st.lworkl, &st.info, 1, 1, 2);
  if (st.info != 0) {
    throw ComputeError(Str() << o.what << ": ARPACK dseupd failed (info = " << st.info
                             << "): " << dseupdMessage(st.info));
  }
  if (st.iparam[4] < st.nev) {
    throw ComputeError(Str() << o.what << ": only " << st.iparam[4] << " of " << st.nev
                             << " eigenvalues converged");
  }
}

// The eigenpairs in ascending order of the eigenvalues, vectors normalised to phi^T M phi = 1.
void sortedNormalisedPairs(const std::vector<double>& d, const Eigen::MatrixXd& Z,
                           const SparseMatrix& M, EigenResult& result) {
  const int nev = static_cast<int>(d.size());
  std::vector<int> order(nev);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return d[a] < d[b]; });
  result.values.resize(nev);
  result.vectors.resize(Z.rows(), nev);
  for (int j = 0; j < nev; ++j) {
    result.values(j) = d[order[j]];
    Eigen::VectorXd phi = Z.col(order[j]);
    const double m = phi.dot(M.selfadjointView<Eigen::Upper>() * phi);
    result.vectors.col(j) = phi / std::sqrt(m);
  }
}

}  // namespace

EigenResult solveEigenproblem(const SparseMatrix& K, const SparseMatrix& M, const EigenOptions& o) {
  const int n = static_cast<int>(K.rows());
  if (o.count < 1 || o.count >= n) {
    throw InputError(Str() << o.what << ": " << o.count << " eigenpairs requested but the "
                           << "problem has " << n << " degrees of freedom (need 1 <= count < " << n
                           << ")");
  }
  SparseMatrix A = K;
  if (o.shift != 0.0) A = K - o.shift * M;
  A.makeCompressed();
  SparseCholesky chol;
  std::string message;
  if (chol.factorize(A, &message) != SparseCholesky::Status::kOk) {
    throw ComputeError(Str() << o.what << ": factorisation of K - sigma M (sigma = " << o.shift
                             << ") failed: " << message);
  }
  return solveEigenproblem(chol, M, o);
}

EigenResult solveEigenproblem(const SparseCholesky& chol, const SparseMatrix& M,
                              const EigenOptions& o) {
  const int n = chol.size();
  if (o.count < 1 || o.count >= n) {
    throw InputError(Str() << o.what << ": " << o.count << " eigenpairs requested but the "
                           << "problem has " << n << " degrees of freedom (need 1 <= count < " << n
                           << ")");
  }

  ArpackState st(n, o);
  EigenResult result;
  const SingleThreadedBlas singleThreaded;  // the operator is applied one vector at a time
  lanczosIterations(chol, M, o, st, result);
  result.iterations = st.iparam[2];
  std::vector<double> d(st.nev);
  Eigen::MatrixXd Z(n, st.nev);
  ritzPairs(o, st, d, Z);
  sortedNormalisedPairs(d, Z, M, result);
  return result;
}

}  // namespace ffriga
