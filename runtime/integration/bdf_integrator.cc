#include "runtime/integration/bdf_integrator.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <vector>

#include <cvode/cvode.h>
#include <cvode/cvode_proj.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "common/base/error.h"
#include "common/base/spelling.h"
#include "runtime/integration/eigen_dense_solver.h"
#include "runtime/integration/structured_solver.h"

namespace ffriga {

struct BdfIntegrator::Impl {
  OdeSystem* system = nullptr;
  SUNContext ctx = nullptr;
  void* cvode = nullptr;
  N_Vector y = nullptr;
  N_Vector atol = nullptr;
  SUNMatrix A = nullptr;
  SUNLinearSolver ls = nullptr;
  std::exception_ptr rhs_error;
  std::string last_message;
  std::unique_ptr<StructuredSolverData> structured;  // set if the structured solver is used

  void check(int flag, const char* call) const {
    if (flag >= 0) return;
    std::string msg = Str() << "CVODE: " << call << " failed with " << CVodeGetReturnFlagName(flag);
    if (!last_message.empty()) msg += ": " + last_message;
    if (flag == CV_REPTD_PROJFUNC_ERR)  // runtime/system/quasi_static_projection.cc
      msg += " (the quasi-static coordinates found no equilibrium: contact points kept "
             "entering and leaving within one projection, as a flat face does against a "
             "penalty stiffer than its elements; README \"Flat faces\")";
    throw ComputeError(msg);
  }

  static int rhs(realtype t, N_Vector y, N_Vector ydot, void* data) {
    Impl* self = static_cast<Impl*>(data);
    try {
      self->system->rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
      for (sunindextype i = 0; i < N_VGetLength(ydot); ++i) {
        if (!std::isfinite(NV_Ith_S(ydot, i))) return 1;  // recoverable: CVODE cuts the step
      }
      return 0;
    } catch (...) {
      self->rhs_error = std::current_exception();
      return -1;
    }
  }

  static int jacobian(realtype t, N_Vector y, N_Vector fy, SUNMatrix J, void* data, N_Vector tmp1,
                      N_Vector, N_Vector) {
    Impl* self = static_cast<Impl*>(data);
    try {
      if (CVodeGetErrWeights(self->cvode, tmp1) < 0) return -1;
      const sunindextype n = N_VGetLength(tmp1);
      std::vector<double> scale(n);
      for (sunindextype i = 0; i < n; ++i) scale[i] = 1.0 / NV_Ith_S(tmp1, i);
      SUNMatZero(J);
      self->system->jacobian(t, N_VGetArrayPointer(y), N_VGetArrayPointer(fy), scale.data(),
                             SUNDenseMatrix_Data(J));
      return 0;
    } catch (...) {
      self->rhs_error = std::current_exception();
      return -1;
    }
  }

  static int linearSystem(realtype t, N_Vector y, N_Vector fy, SUNMatrix A, booleantype jok,
                          booleantype* jcur, realtype gamma, void* data, N_Vector tmp1,
                          N_Vector tmp2, N_Vector tmp3) {
    Impl* self = static_cast<Impl*>(data);
    return structuredLinearSystem(t, y, fy, A, jok, jcur, gamma, self->structured.get(), tmp1, tmp2,
                                  tmp3);
  }

  static int project(realtype t, N_Vector ycur, N_Vector corr, realtype, N_Vector, void* data) {
    Impl* self = static_cast<Impl*>(data);
    try {
      return self->system->project(t, N_VGetArrayPointer(ycur), N_VGetArrayPointer(corr)) ? 0 : 1;
    } catch (...) {
      self->rhs_error = std::current_exception();
      return -1;
    }
  }

  static void errorHandler(int, const char* module, const char* function, char* msg, void* data) {
    static_cast<Impl*>(data)->last_message = Str() << module << "/" << function << ": " << msg;
  }
};

BdfIntegrator::BdfIntegrator(OdeSystem& system, double t0, const Eigen::VectorXd& y0,
                             const IntegratorOptions& o)
    : impl_(new Impl) {
  Impl& m = *impl_;
  m.system = &system;
  const int n = system.size();
  FFRIGA_CHECK(y0.size() == n, "initial state has " << y0.size() << " entries, system " << n);
  FFRIGA_CHECK(o.atol.size() == n, "atol has " << o.atol.size() << " entries, system " << n);
  if (SUNContext_Create(nullptr, &m.ctx) != 0) throw ComputeError("SUNContext_Create failed");
  m.y = N_VNew_Serial(n, m.ctx);
  m.atol = N_VNew_Serial(n, m.ctx);
  if (!m.y || !m.atol) throw ComputeError("CVODE: N_VNew_Serial failed (out of memory?)");
  for (int i = 0; i < n; ++i) {
    NV_Ith_S(m.y, i) = y0(i);
    NV_Ith_S(m.atol, i) = o.atol(i);
  }
  m.cvode = CVodeCreate(CV_BDF, m.ctx);
  if (!m.cvode) throw ComputeError("CVODE: CVodeCreate failed (out of memory?)");
  m.check(CVodeSetErrHandlerFn(m.cvode, &Impl::errorHandler, &m), "CVodeSetErrHandlerFn");
  m.check(CVodeInit(m.cvode, &Impl::rhs, t0, m.y), "CVodeInit");
  m.check(CVodeSetUserData(m.cvode, &m), "CVodeSetUserData");
  m.check(CVodeSVtolerances(m.cvode, o.rtol, m.atol), "CVodeSVtolerances");
  m.check(CVodeSetMaxNumSteps(m.cvode, o.max_steps), "CVodeSetMaxNumSteps");
  m.check(CVodeSetMaxOrd(m.cvode, o.max_order), "CVodeSetMaxOrd");
  if (o.max_step > 0.0) m.check(CVodeSetMaxStep(m.cvode, o.max_step), "CVodeSetMaxStep");
  if (o.initial_step > 0.0) m.check(CVodeSetInitStep(m.cvode, o.initial_step), "CVodeSetInitStep");
  // Constraints: CVODE projects onto the constraint manifold after every step. The error
  // estimate is left unprojected (CVodeSetProjErrEst off): its constraint-normal part is
  // of the order of the projection itself, and the joint scenes' tolerances are set for it.
  if (system.hasConstraints()) {
    m.check(CVodeSetProjFn(m.cvode, &Impl::project), "CVodeSetProjFn");
    m.check(CVodeSetProjErrEst(m.cvode, SUNFALSE), "CVodeSetProjErrEst");
  }
  // Structured Newton matrix if asked for (kAuto) and the system has it at the initial state.
  Eigen::VectorXd scale0 = Eigen::VectorXd::Ones(n);
  for (int i = 0; i < n; ++i) scale0(i) = std::max(std::abs(y0(i)), o.atol(i) / o.rtol);
  if (o.linear_solver == LinearSolverKind::kAuto) {
    auto data = std::make_unique<StructuredSolverData>();
    if (system.structuredJacobian(t0, y0.data(), scale0.data(), data->J)) {
      data->system = &system;
      data->cvode = m.cvode;
      data->error = &m.rhs_error;
      data->J = StructuredJacobian();  // evaluated again at CVODE's first setup
      m.structured = std::move(data);
    }
  }
  if (m.structured) {
    m.A = SUNDenseMatrix(1, 1, m.ctx);  // placeholder: the Newton matrix is never dense
    if (!m.A) throw ComputeError("CVODE: SUNDenseMatrix failed (out of memory?)");
    m.ls = newStructuredSolver(m.ctx, m.structured.get());
    if (!m.ls) throw ComputeError("CVODE: creating the linear solver failed (out of memory?)");
    m.check(CVodeSetLinearSolver(m.cvode, m.ls, m.A), "CVodeSetLinearSolver");
    m.check(CVodeSetLinSysFn(m.cvode, &Impl::linearSystem), "CVodeSetLinSysFn");
    return;
  }
  m.A = SUNDenseMatrix(n, n, m.ctx);
  if (!m.A) throw ComputeError("CVODE: SUNDenseMatrix failed (out of memory?)");
  m.ls = o.linear_solver == LinearSolverKind::kSundialsDense ? SUNLinSol_Dense(m.y, m.A, m.ctx)
                                                             : newEigenDenseSolver(m.ctx);
  if (!m.ls) throw ComputeError("CVODE: creating the linear solver failed (out of memory?)");
  m.check(CVodeSetLinearSolver(m.cvode, m.ls, m.A), "CVodeSetLinearSolver");
  // The system's own Jacobian if it has one (probe with a zero-size call is not possible:
  // ask at the initial state).
  {
    Eigen::VectorXd f(n), scale = Eigen::VectorXd::Ones(n);
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n, n);
    system.rhs(t0, y0.data(), f.data());
    if (system.jacobian(t0, y0.data(), f.data(), scale.data(), J.data()))
      m.check(CVodeSetJacFn(m.cvode, &Impl::jacobian), "CVodeSetJacFn");
  }
}

bool BdfIntegrator::structured() const {
  return impl_->structured != nullptr;
}

BdfIntegrator::~BdfIntegrator() {
  Impl& m = *impl_;
  if (m.cvode) CVodeFree(&m.cvode);
  if (m.ls) SUNLinSolFree(m.ls);
  if (m.A) SUNMatDestroy(m.A);
  if (m.y) N_VDestroy(m.y);
  if (m.atol) N_VDestroy(m.atol);
  if (m.ctx) SUNContext_Free(&m.ctx);
}

void BdfIntegrator::advance(double tout, Eigen::VectorXd& y) {
  Impl& m = *impl_;
  realtype t = 0.0;
  const int flag = CVode(m.cvode, tout, m.y, &t, CV_NORMAL);
  if (m.rhs_error) {
    std::exception_ptr e = m.rhs_error;
    m.rhs_error = nullptr;
    std::rethrow_exception(e);
  }
  m.check(flag, "CVode");
  y = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(m.y), m.system->size());
}

double BdfIntegrator::step() {
  Impl& m = *impl_;
  realtype t = 0.0;
  const int flag = CVode(m.cvode, std::numeric_limits<double>::max(), m.y, &t, CV_ONE_STEP);
  if (m.rhs_error) {
    std::exception_ptr e = m.rhs_error;
    m.rhs_error = nullptr;
    std::rethrow_exception(e);
  }
  m.check(flag, "CVode");
  return t;
}

void BdfIntegrator::setMaxStep(double h) {
  impl_->check(CVodeSetMaxStep(impl_->cvode, h), "CVodeSetMaxStep");
}

void BdfIntegrator::setStopTime(double t) {
  impl_->check(CVodeSetStopTime(impl_->cvode, t), "CVodeSetStopTime");
}

void BdfIntegrator::interpolate(double t, Eigen::VectorXd& y) const {
  const int n = impl_->system->size();
  N_Vector dky = N_VNew_Serial(n, impl_->ctx);
  if (!dky) throw ComputeError("CVODE: N_VNew_Serial failed");
  const int flag = CVodeGetDky(impl_->cvode, t, 0, dky);
  y = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(dky), n);
  N_VDestroy(dky);
  impl_->check(flag, "CVodeGetDky");
}

double BdfIntegrator::time() const {
  realtype t = 0.0;
  impl_->check(CVodeGetCurrentTime(impl_->cvode, &t), "CVodeGetCurrentTime");
  return t;
}

Eigen::VectorXd BdfIntegrator::currentState() const {
  const int n = impl_->system->size();
  N_Vector dky = N_VNew_Serial(n, impl_->ctx);
  if (!dky) throw ComputeError("CVODE: N_VNew_Serial failed");
  const int flag = CVodeGetDky(impl_->cvode, time(), 0, dky);
  Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(dky), n);
  N_VDestroy(dky);
  impl_->check(flag, "CVodeGetDky");
  return y;
}

IntegratorStats BdfIntegrator::stats() const {
  const Impl& m = *impl_;
  IntegratorStats s;
  m.check(CVodeGetNumSteps(m.cvode, &s.steps), "CVodeGetNumSteps");
  m.check(CVodeGetNumRhsEvals(m.cvode, &s.rhs_evals), "CVodeGetNumRhsEvals");
  m.check(CVodeGetNumJacEvals(m.cvode, &s.jacobian_evals), "CVodeGetNumJacEvals");
  m.check(CVodeGetNumLinRhsEvals(m.cvode, &s.jacobian_rhs_evals), "CVodeGetNumLinRhsEvals");
  m.check(CVodeGetNumLinSolvSetups(m.cvode, &s.linear_setups), "CVodeGetNumLinSolvSetups");
  m.check(CVodeGetNumErrTestFails(m.cvode, &s.error_test_failures), "CVodeGetNumErrTestFails");
  m.check(CVodeGetNumNonlinSolvIters(m.cvode, &s.nonlinear_iterations),
          "CVodeGetNumNonlinSolvIters");
  m.check(CVodeGetNumNonlinSolvConvFails(m.cvode, &s.convergence_failures),
          "CVodeGetNumNonlinSolvConvFails");
  m.check(CVodeGetLastOrder(m.cvode, &s.last_order), "CVodeGetLastOrder");
  m.check(CVodeGetLastStep(m.cvode, &s.last_step), "CVodeGetLastStep");
  return s;
}

namespace {
const Spelling<LinearSolverKind> kLinearSolvers[] = {{"structured", LinearSolverKind::kAuto},
                                                     {"dense", LinearSolverKind::kEigenDense}};
}  // namespace

bool parseKind(std::string_view text, LinearSolverKind* kind) {
  return parseSpelling(kLinearSolvers, text, kind);
}

}  // namespace ffriga
