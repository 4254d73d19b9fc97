#include "runtime/forces/line_force.h"

#include <cmath>

#include "common/base/error.h"
#include "runtime/bodies/marker_kinematics.h"

namespace ffriga {

LineForce::LineForce(std::string name, MarkerEnd a, MarkerEnd b)
    : ForceElement(std::move(name), a.body, b.body), a_(std::move(a)), b_(std::move(b)) {
  FFRIGA_CHECK(b_.model != nullptr, "force element '" << this->name() << "': end b must be a body");
}

void LineForce::addForces(const ForceContext& at, std::vector<Eigen::VectorXd>& h,
                          const ForceStates& states) {
  const int a = bodyA(), b = bodyB();
  apply(a >= 0 ? at.positions(a) : nullptr, a >= 0 ? at.velocities(a) : nullptr, at.positions(b),
        at.velocities(b), a >= 0 ? h[a].data() : nullptr, h[b].data(),
        states.line_forces ? &(*states.line_forces)[slot()] : nullptr);
}

void LineForce::apply(const double* spA, const double* svA, const double* spB, const double* svB,
                      double* ha, double* hb, LineForceState* state) const {
  MarkerKinematics ka, kb;
  if (a_.model)
    markerPoint(*a_.model, spA, svA, a_.marker, ka);
  else
    groundKinematics(a_.marker.x0, ka);
  markerPoint(*b_.model, spB, svB, b_.marker, kb);
  const Eigen::Vector3d d = kb.value - ka.value;
  const double l = d.norm();
  if (!(l > 0.0))
    throw ComputeError(Str() << "force element '" << name() << "': its two points coincide "
                             << "(no line of action)");
  const Eigen::Vector3d n = d / l;
  const double rate = n.dot(kb.rate - ka.rate);
  const double T = tension(l, rate);
  if (a_.model) addMarkerForce(*a_.model, spA, a_.marker, T * n, ha);
  addMarkerForce(*b_.model, spB, b_.marker, -T * n, hb);
  if (state) *state = LineForceState{l, rate, T, energy(l), dissipation(l, rate)};
}

}  // namespace ffriga
