// What the time integrator sees of the physics: a first-order system dy/dt = f(t, y) of
// fixed size (Chrono's ChIntegrable idea). The integrator never looks inside.
#pragma once

#include "runtime/integration/structured_newton.h"

namespace ffriga {

class OdeSystem {
 public:
  virtual ~OdeSystem() = default;
  virtual int size() const = 0;
  // dy/dt at (t, y). May throw; the integrator stops and rethrows.
  virtual void rhs(double t, const double* y, double* ydot) = 0;
  // Optional Jacobian J = df/dy at (t, y) with f = f(t, y) given, into the column-major n x n
  // array J (zeroed by the caller). `scale`: a typical magnitude of each y_j (difference
  // quotient increments). Returns false if the system provides none (the integrator then
  // uses difference quotients of its own).
  virtual bool jacobian(double t, const double* y, const double* f, const double* scale,
                        double* J) {
    (void)t, (void)y, (void)f, (void)scale, (void)J;
    return false;
  }
  // Optional Jacobian in the structured form J = D + U V^T of
  // runtime/integration/structured_newton.h at (t, y); `scale` as for jacobian(). Returns false if
  // the system has none, or not at this state (the integrator then uses the dense Newton matrix).
  virtual bool structuredJacobian(double t, const double* y, const double* scale,
                                  StructuredJacobian& J) {
    (void)t, (void)y, (void)scale, (void)J;
    return false;
  }
  // Called by the driver between output intervals to project invariants (unit quaternions).
  virtual void normalize(double* y) const { (void)y; }
  // Constraints (joints): a system with hasConstraints() keeps its state on a manifold the
  // integrator projects onto after every step (CVodeSetProjFn): corr = P(y) - y. Returns
  // false if the projection failed (the integrator then retries with a smaller step).
  virtual bool hasConstraints() const { return false; }
  virtual bool project(double t, const double* y, double* corr) {
    (void)t, (void)y, (void)corr;
    return false;
  }
};

}  // namespace ffriga
