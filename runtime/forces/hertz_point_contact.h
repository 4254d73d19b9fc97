// Hertz's contact law between two rigid spheres whose centres are the two markers
// (runtime/forces/line_force.h), the rigid-body reference of paper Sect. 7 (Fig. 17):
//   delta = R_a + R_b - l  (approach),   F = K delta^(3/2) for delta > 0, else 0,
//   K = 4/3 E* sqrt(R*)    (common/mechanics/hertz.h),   energy 2/5 K delta^(5/2),
// pushing the spheres apart (tension -F). Radii in m, K in N/m^(3/2).
#pragma once

#include "common/mechanics/hertz.h"
#include "runtime/forces/line_force.h"

namespace ffriga {

class HertzPointContact : public LineForce {
 public:
  HertzPointContact(std::string name, MarkerEnd a, MarkerEnd b, const HertzSphere& sa,
                    const HertzSphere& sb);
  const char* kind() const override { return "hertz_contact"; }
  bool isContact() const override { return true; }
  double stiffness() const { return K_; }
  double radiusSum() const { return radii_; }

 protected:
  double tension(double l, double rate) const override;
  double energy(double l) const override;

 private:
  double K_, radii_;
};

}  // namespace ffriga
