#include "runtime/eigen_dense_solver.h"

#include <cmath>
#include <new>

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <Eigen/Dense>

namespace ffriga {

namespace {

struct Content {
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  sunindextype last_flag = 0;
};

Content* content(SUNLinearSolver S) {
  return static_cast<Content*>(S->content);
}

SUNLinearSolver_Type getType(SUNLinearSolver) {
  return SUNLINEARSOLVER_DIRECT;
}
SUNLinearSolver_ID getId(SUNLinearSolver) {
  return SUNLINEARSOLVER_CUSTOM;
}
int initialize(SUNLinearSolver S) {
  content(S)->last_flag = SUNLS_SUCCESS;
  return SUNLS_SUCCESS;
}

int setup(SUNLinearSolver S, SUNMatrix A) {
  if (SUNMatGetID(A) != SUNMATRIX_DENSE) return SUNLS_ILL_INPUT;
  const sunindextype n = SUNDenseMatrix_Rows(A);
  const Eigen::Map<const Eigen::MatrixXd> N(SUNDenseMatrix_Data(A), n, n);
  Content* c = content(S);
  c->lu.compute(N);
  // Singular or non-finite: let CVODE cut the step (recoverable failure).
  const auto d = c->lu.matrixLU().diagonal();
  const bool bad = !d.allFinite() || (d.array() == 0.0).any();
  c->last_flag = bad ? SUNLS_LUFACT_FAIL : SUNLS_SUCCESS;
  return static_cast<int>(c->last_flag);
}

int solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, realtype) {
  const sunindextype n = SUNDenseMatrix_Rows(A);
  Eigen::Map<Eigen::VectorXd> X(N_VGetArrayPointer(x), n);
  const Eigen::Map<const Eigen::VectorXd> B(N_VGetArrayPointer(b), n);
  X = content(S)->lu.solve(B);
  content(S)->last_flag = X.allFinite() ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_REC;
  return static_cast<int>(content(S)->last_flag);
}

sunindextype lastFlag(SUNLinearSolver S) {
  return content(S)->last_flag;
}

int freeSolver(SUNLinearSolver S) {
  if (!S) return SUNLS_SUCCESS;
  delete content(S);
  S->content = nullptr;
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}

}  // namespace

SUNLinearSolver newEigenDenseSolver(SUNContext ctx) {
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) return nullptr;
  S->content = new (std::nothrow) Content;
  if (!S->content) {
    SUNLinSolFreeEmpty(S);
    return nullptr;
  }
  // Eigen would parallelise the factorisation with OpenMP; at this size, and with the contact
  // loop owning the threads, one thread is faster.
  Eigen::setNbThreads(1);
  S->ops->gettype = getType;
  S->ops->getid = getId;
  S->ops->initialize = initialize;
  S->ops->setup = setup;
  S->ops->solve = solve;
  S->ops->lastflag = lastFlag;
  S->ops->free = freeSolver;
  return S;
}

}  // namespace ffriga
