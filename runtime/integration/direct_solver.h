// A custom SUNDIALS direct linear solver (SUNLINEARSOLVER_DIRECT) around an object that
// implements setup and solve with SUNDIALS return codes (SUNLS_SUCCESS, SUNLS_LUFACT_FAIL or
// SUNLS_PACKAGE_FAIL_REC for recoverable failures: CVODE then retries with a smaller step).
// The SUNDIALS boilerplate (type, id, last flag, free) lives here once.
#pragma once

#include <memory>

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

namespace ffriga {

class DirectSolverImpl {
 public:
  virtual ~DirectSolverImpl() = default;
  virtual int setup(SUNMatrix A) = 0;
  // x = A^-1 b for the A of the last setup.
  virtual int solve(SUNMatrix A, N_Vector x, N_Vector b) = 0;
};

// Takes ownership of `impl`; returns nullptr if out of memory. Free with SUNLinSolFree.
SUNLinearSolver newDirectSolver(SUNContext ctx, std::unique_ptr<DirectSolverImpl> impl);

}  // namespace ffriga
