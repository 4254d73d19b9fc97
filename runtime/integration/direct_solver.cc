#include "runtime/integration/direct_solver.h"

#include <new>

namespace ffriga {

namespace {

struct Content {
  std::unique_ptr<DirectSolverImpl> impl;
  sunindextype last_flag = SUNLS_SUCCESS;
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
  content(S)->last_flag = content(S)->impl->setup(A);
  return static_cast<int>(content(S)->last_flag);
}
int solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, realtype) {
  content(S)->last_flag = content(S)->impl->solve(A, x, b);
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

SUNLinearSolver newDirectSolver(SUNContext ctx, std::unique_ptr<DirectSolverImpl> impl) {
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) return nullptr;
  Content* c = new (std::nothrow) Content;
  if (!c) {
    SUNLinSolFreeEmpty(S);
    return nullptr;
  }
  c->impl = std::move(impl);
  S->content = c;
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
