// Force elements (runtime/forces/force_element.h) that act along the line between two
// marker points: with
// d = R_b - R_a, length l = |d|, direction n = d / l and rate dl/dt = n . (dR_b/dt - dR_a/dt)
// (runtime/bodies/marker_kinematics.h), a tension T(l, dl/dt) (N, > 0 pulls the ends
// together) acts as the force +T n on end a and -T n on end b; their generalised forces are
// G^T f at each marker (Eq. 18 for a point force). Laws: runtime/forces/spring_damper.h,
// runtime/forces/hertz_point_contact.h.
#pragma once

#include <string>

#include <Eigen/Dense>

#include "runtime/bodies/body_marker.h"
#include "runtime/forces/force_element.h"

namespace ffriga {

struct LineForceState {
  double length = 0.0;   // m
  double rate = 0.0;     // m/s
  double tension = 0.0;  // N (> 0 pulls together; negative: pushes apart)
  double energy = 0.0;   // J, potential of the conservative part
  double dissipation = 0.0;  // W, power its dissipative part takes out of the system (>= 0)
};

class LineForce : public ForceElement {
 public:
  LineForce(std::string name, MarkerEnd a, MarkerEnd b);
  const MarkerEnd& end(int i) const { return i == 0 ? a_ : b_; }
  bool isContact() const override { return false; }
  void addForces(const ForceContext& at, std::vector<Eigen::VectorXd>& h,
                 const ForceStates& states) override;

  // Adds the generalised forces at the ends' states (nullptr for the ground) to ha, hb
  // (each body's numVelocities entries; ha unused for the ground).
  void apply(const double* spA, const double* svA, const double* spB, const double* svB,
             double* ha, double* hb, LineForceState* state) const;

 protected:
  virtual double tension(double length, double rate) const = 0;
  virtual double energy(double length) const = 0;
  // The power (W) the element's dissipative part takes out of the system: (T - V'(l)) l'.
  virtual double dissipation(double /*length*/, double /*rate*/) const { return 0.0; }

 private:
  MarkerEnd a_, b_;
};

}  // namespace ffriga
