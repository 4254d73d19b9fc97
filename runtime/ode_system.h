// What the time integrator sees of the physics: a first-order system dy/dt = f(t, y) of
// fixed size (Chrono's ChIntegrable idea). The integrator never looks inside.
#pragma once

namespace ffriga {

class OdeSystem {
 public:
  virtual ~OdeSystem() = default;
  virtual int size() const = 0;
  // dy/dt at (t, y). May throw; the integrator stops and rethrows.
  virtual void rhs(double t, const double* y, double* ydot) = 0;
  // Called by the driver between output intervals to project invariants (unit quaternions).
  virtual void normalize(double* y) const { (void)y; }
};

}  // namespace ffriga
