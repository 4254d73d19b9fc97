#include "runtime/integration/eigen_dense_solver.h"

#include <new>

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <Eigen/Dense>

#include "runtime/integration/direct_solver.h"

namespace ffriga {

namespace {

class EigenLu : public DirectSolverImpl {
 public:
  int setup(SUNMatrix A) override {
    if (SUNMatGetID(A) != SUNMATRIX_DENSE) return SUNLS_ILL_INPUT;
    const sunindextype n = SUNDenseMatrix_Rows(A);
    lu_.compute(Eigen::Map<const Eigen::MatrixXd>(SUNDenseMatrix_Data(A), n, n));
    // Singular or non-finite: let CVODE cut the step (recoverable failure).
    const auto d = lu_.matrixLU().diagonal();
    return !d.allFinite() || (d.array() == 0.0).any() ? SUNLS_LUFACT_FAIL : SUNLS_SUCCESS;
  }
  int solve(SUNMatrix A, N_Vector x, N_Vector b) override {
    const sunindextype n = SUNDenseMatrix_Rows(A);
    Eigen::Map<Eigen::VectorXd> X(N_VGetArrayPointer(x), n);
    X = lu_.solve(Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(b), n));
    return X.allFinite() ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_REC;
  }

 private:
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
};

}  // namespace

SUNLinearSolver newEigenDenseSolver(SUNContext ctx) {
  std::unique_ptr<DirectSolverImpl> impl(new (std::nothrow) EigenLu);
  if (!impl) return nullptr;
  // Eigen would parallelise the factorisation with OpenMP; at this size, and with the contact
  // loop owning the threads, one thread is faster.
  Eigen::setNbThreads(1);
  return newDirectSolver(ctx, std::move(impl));
}

}  // namespace ffriga
