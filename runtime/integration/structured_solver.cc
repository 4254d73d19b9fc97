#include "runtime/integration/structured_solver.h"

#include <new>
#include <vector>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>

#include "runtime/integration/direct_solver.h"

namespace ffriga {

namespace {

// The factorisation happens in structuredLinearSystem, which knows gamma and the state;
// setup only reports its outcome.
class StructuredImpl : public DirectSolverImpl {
 public:
  explicit StructuredImpl(StructuredSolverData* data) : data_(data) {}
  int setup(SUNMatrix) override { return data_->factored ? SUNLS_SUCCESS : SUNLS_LUFACT_FAIL; }
  int solve(SUNMatrix, N_Vector x, N_Vector b) override {
    data_->N.solve(N_VGetArrayPointer(b), N_VGetArrayPointer(x));
    const Eigen::Map<const Eigen::VectorXd> X(N_VGetArrayPointer(x), N_VGetLength(x));
    return X.allFinite() ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_REC;
  }

 private:
  StructuredSolverData* data_;
};

}  // namespace

SUNLinearSolver newStructuredSolver(SUNContext ctx, StructuredSolverData* data) {
  std::unique_ptr<DirectSolverImpl> impl(new (std::nothrow) StructuredImpl(data));
  if (!impl) return nullptr;
  // Eigen would run the n x r products on OpenMP threads; at these sizes, and with the
  // contact loop owning the threads, one thread is faster (measured: 5x slower otherwise).
  Eigen::setNbThreads(1);
  return newDirectSolver(ctx, std::move(impl));
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
