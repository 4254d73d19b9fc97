#include "runtime/structured_solver.h"

#include <new>
#include <vector>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>

namespace ffriga {

namespace {

struct Content {
  StructuredSolverData* data = nullptr;
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
// The factorisation happens in structuredLinearSystem, which knows gamma and the state.
int setup(SUNLinearSolver S, SUNMatrix) {
  const bool ok = content(S)->data->factored;
  content(S)->last_flag = ok ? SUNLS_SUCCESS : SUNLS_LUFACT_FAIL;
  return static_cast<int>(content(S)->last_flag);
}
int solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, realtype) {
  StructuredSolverData& d = *content(S)->data;
  d.N.solve(N_VGetArrayPointer(b), N_VGetArrayPointer(x));
  const Eigen::Map<const Eigen::VectorXd> X(N_VGetArrayPointer(x), N_VGetLength(x));
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

SUNLinearSolver newStructuredSolver(SUNContext ctx, StructuredSolverData* data) {
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) return nullptr;
  Content* c = new (std::nothrow) Content;
  if (!c) {
    SUNLinSolFreeEmpty(S);
    return nullptr;
  }
  c->data = data;
  S->content = c;
  // Eigen would run the n x r products on OpenMP threads; at these sizes, and with the
  // contact loop owning the threads, one thread is faster (measured: 5x slower otherwise).
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

int structuredLinearSystem(realtype t, N_Vector y, N_Vector, SUNMatrix, booleantype jok,
                           booleantype* jcur, realtype gamma, void* user_data, N_Vector tmp1,
                           N_Vector, N_Vector) {
  StructuredSolverData& d = *static_cast<StructuredSolverData*>(user_data);
  d.factored = false;
  try {
    if (!jok || d.J.n == 0) {
      if (CVodeGetErrWeights(d.cvode, tmp1) < 0) return -1;
      const sunindextype n = N_VGetLength(tmp1);
      std::vector<double> scale(n);
      for (sunindextype i = 0; i < n; ++i) scale[i] = 1.0 / NV_Ith_S(tmp1, i);
      if (!d.system->structuredJacobian(t, N_VGetArrayPointer(y), scale.data(), d.J)) return -1;
      *jcur = SUNTRUE;
    } else {
      *jcur = SUNFALSE;
    }
    d.factored = d.N.factor(gamma, d.J);
    return d.factored ? 0 : 1;  // 1: recoverable, CVODE retries with a smaller step
  } catch (...) {
    if (d.error) *d.error = std::current_exception();
    return -1;
  }
}

}  // namespace ffriga
