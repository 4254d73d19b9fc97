// Linear spring-damper between two markers (runtime/forces/line_force.h):
//   T = k (l - l0) + c dl/dt,   energy 1/2 k (l - l0)^2,
// k in N/m, c in N s/m, free length l0 in m.
#pragma once

#include "runtime/forces/line_force.h"

namespace ffriga {

class SpringDamper : public LineForce {
 public:
  SpringDamper(std::string name, MarkerEnd a, MarkerEnd b, double stiffness, double damping,
               double free_length);
  const char* kind() const override { return "spring_damper"; }

 protected:
  double tension(double l, double rate) const override { return k_ * (l - l0_) + c_ * rate; }
  double energy(double l) const override { return 0.5 * k_ * (l - l0_) * (l - l0_); }
  double dissipation(double, double rate) const override { return c_ * rate * rate; }

 private:
  double k_, c_, l0_;
};

}  // namespace ffriga
