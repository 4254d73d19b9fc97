// SUNDIALS linear solver for CVODE's Newton matrix N = I - gamma J in the structured form of
// runtime/integration/structured_newton.h (Woodbury), for systems that provide
// OdeSystem::structuredJacobian.
//
// Wiring (runtime/bdf_integrator.cc): CVODE's user linear-system function (CVodeSetLinSysFn)
// receives gamma and the state and decides, by CVODE's own heuristics (jok), whether the
// Jacobian may be reused; it evaluates the structured Jacobian when needed and factorises N.
// The SUNLinearSolver is a direct solver whose setup is a no-op and whose solve applies the
// factorisation. CVODE's SUNMatrix is a 1 x 1 placeholder: no dense n x n matrix exists.
#pragma once

#include <exception>
#include <memory>

#include <cvode/cvode_ls.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

#include "runtime/integration/ode_system.h"
#include "runtime/integration/structured_newton.h"

namespace ffriga {

struct StructuredSolverData {
  OdeSystem* system = nullptr;
  void* cvode = nullptr;                // for the error weights (difference-quotient increments)
  std::exception_ptr* error = nullptr;  // where a system exception is parked for rethrow
  StructuredJacobian J;
  StructuredNewtonMatrix N;
  bool factored = false;
};

// The linear solver (free with SUNLinSolFree; `data` must outlive it); nullptr if out of
// memory.
SUNLinearSolver newStructuredSolver(SUNContext ctx, StructuredSolverData* data);

// CVLsLinSysFn for CVodeSetLinSysFn, with user_data = the StructuredSolverData.
int structuredLinearSystem(realtype t, N_Vector y, N_Vector fy, SUNMatrix A, booleantype jok,
                           booleantype* jcur, realtype gamma, void* user_data, N_Vector tmp1,
                           N_Vector tmp2, N_Vector tmp3);

}  // namespace ffriga
