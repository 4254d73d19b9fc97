// Stiff time integration of an OdeSystem with SUNDIALS CVODE (BDF, variable order 1..5 and
// variable step, Newton iteration with a direct linear solver: the structured Woodbury solve
// of runtime/integration/structured_solver.h where the system provides a structured Jacobian, else
// a dense LU (Eigen's, runtime/integration/eigen_dense_solver.h) of the system's dense Jacobian or
// of CVODE's difference quotients). The paper uses MATLAB's ode15s (NDF/BDF); CVODE's BDF is its
// direct equivalent.
//
// Output times are reached with CV_NORMAL: CVODE steps past tout with its own step size and
// interpolates (CVodeGetDky), so requested outputs never force small steps. Every SUNDIALS
// return code is checked; failures throw ComputeError with CVODE's flag name and message.
// CVODE's own printing is silenced (its last message is kept for the exception).
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include <Eigen/Dense>

#include "runtime/integration/ode_system.h"

namespace ffriga {

// Newton matrix: structured (Woodbury, runtime/integration/structured_newton.h) where the system
// provides a structured Jacobian, else Eigen's blocked dense LU; kEigenDense and
// kSundialsDense (SUNDIALS' reference LU) force a dense n x n matrix.
enum class LinearSolverKind { kAuto, kEigenDense, kSundialsDense };
// The scene's words (integrator.linear_solver): "structured" (kAuto), "dense" (kEigenDense).
bool parseKind(std::string_view text, LinearSolverKind* kind);

struct IntegratorOptions {
  LinearSolverKind linear_solver = LinearSolverKind::kAuto;
  double rtol = 1e-6;         // relative tolerance (dimensionless)
  Eigen::VectorXd atol;       // absolute tolerance per component (units of y)
  double max_step = 0.0;      // s; 0: unlimited
  double initial_step = 0.0;  // s; 0: CVODE's estimate
  long max_steps = 1000000;   // internal steps per call of advance()
  // BDF orders 4 and 5 are not A-stable (stability angles 73 and 51 degrees). Penalty
  // contact stiffens modes whose modal damping was set for the free body, leaving lightly
  // damped eigenvalues of large modulus near the imaginary axis: there orders 4-5 are
  // stability-limited to tiny steps and CVODE's error test can fail for good (the paper's
  // Sect. 5 impacts, benchmarks/impact2d.py: order 5 fails sphere2d_g6 and needs 1.5-3x the
  // steps of order 3 on the others). Order 3 (A(86 deg)-stable) ran every 2D model fastest.
  // But order 3 is not stable on the imaginary axis either: undamped elastic modes resolved
  // over thousands of periods grow (measured after the Sect. 5 impact: elastic energy x600
  // in 3 ms; a bouncing ball chattered). Such runs set 2 (A-stable, slightly dissipative).
  int max_order = 3;
};

struct IntegratorStats {
  long steps = 0;
  long rhs_evals = 0;  // by the integrator (excluding difference-quotient Jacobians)
  long jacobian_evals = 0;
  long jacobian_rhs_evals = 0;  // right-hand sides spent on difference-quotient Jacobians
  long linear_setups = 0;       // Newton matrix factorisations
  long error_test_failures = 0;
  long nonlinear_iterations = 0;
  long convergence_failures = 0;
  int last_order = 0;
  double last_step = 0.0;  // s
};

class BdfIntegrator {
 public:
  BdfIntegrator(OdeSystem& system, double t0, const Eigen::VectorXd& y0,
                const IntegratorOptions& options);
  ~BdfIntegrator();
  BdfIntegrator(const BdfIntegrator&) = delete;
  BdfIntegrator& operator=(const BdfIntegrator&) = delete;

  // Integrates to tout and stores y(tout) (interpolated). Throws ComputeError on failure,
  // after which time() and state() hold the last successful internal step.
  void advance(double tout, Eigen::VectorXd& y);
  // One internal step (CV_ONE_STEP), never past the stop time; returns the time reached.
  double step();
  void setStopTime(double t);
  // Largest step from now on (s; 0: unlimited).
  void setMaxStep(double h);
  // Solution at t in the last step's interval [time() - last step, time()], by CVODE's
  // interpolating polynomial (CVodeGetDky).
  void interpolate(double t, Eigen::VectorXd& y) const;
  // Time of the last internal step and the solution there.
  double time() const;
  Eigen::VectorXd currentState() const;
  IntegratorStats stats() const;
  // True if the structured Newton matrix is in use (LinearSolverKind::kAuto, and the system
  // provided a structured Jacobian at the initial state).
  bool structured() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ffriga
