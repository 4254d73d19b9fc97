// The multibody system: any number of flexible bodies (runtime/body_model.h), gravity and
// contact pairs (runtime/contact_pair.h), in first-order form for the integrator
// (paper Eq. 1 for every body):
//
//   y = [s_p(body 0), s_p(body 1), ..., s_v(body 0), s_v(body 1), ...],
//   dy/dt = [position rates; accelerations from M(q) dz = h_d + h_b - h_omega - h_e].
//
// Contact forces are the discrete forces h_d (Eq. 18); each pair adds equal and opposite
// forces to its two bodies.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "runtime/body_model.h"
#include "runtime/contact_pair.h"
#include "runtime/ode_system.h"

namespace ffriga {

struct SystemEnergies {
  double kinetic = 0.0;  // J
  double elastic = 0.0;  // J, 1/2 q^T Ke q summed over bodies
  double gravity = 0.0;  // J, potential of gravity
  double contact = 0.0;  // J, penalty energy of the active contact points
};

class MultibodySystem : public OdeSystem {
 public:
  int addBody(std::unique_ptr<BodyModel> body);  // returns the body's index
  void addContact(std::unique_ptr<ContactPair> pair);
  void setGravity(const Eigen::Vector3d& g) { gravity_ = g; }
  const Eigen::Vector3d& gravity() const { return gravity_; }

  int numBodies() const { return static_cast<int>(bodies_.size()); }
  const BodyModel& body(int b) const { return *bodies_[b]; }
  BodyModel& body(int b) { return *bodies_[b]; }
  int numContacts() const { return static_cast<int>(contacts_.size()); }
  const ContactPair& contact(int c) const { return *contacts_[c]; }
  ContactPair& contact(int c) { return *contacts_[c]; }

  int size() const override { return size_; }
  int positionOffset(int b) const { return pos_offset_[b]; }
  int velocityOffset(int b) const { return vel_offset_[b]; }

  void rhs(double t, const double* y, double* ydot) override;
  void normalize(double* y) const override;
  // Newton-matrix Jacobian: difference quotients of each body's own rates with the contact
  // forces frozen (cheap: no contact search), plus the analytic low-rank contact stiffness
  // (contact_pair.h) mapped by M(q)^-1.
  bool jacobian(double t, const double* y, const double* f, const double* scale,
                double* J) override;

  // The pairs' diagnostics at the state of the latest rhs() call. CVODE evaluates the
  // right-hand side last at the final Newton iterate of an accepted step, so after a step
  // this is the contact state at its end to within the Newton tolerance, at no extra cost.
  const std::vector<ContactState>& lastRhsContacts() const { return rhs_states_; }
  // The same Jacobian in structured form (runtime/structured_newton.h), available when every
  // body has Me = E and diagonal Ke, De: D holds the elastic pairs; U V^T the rigid columns
  // (difference quotients as above), the rigid-elastic inertial coupling through M(q)^-1
  // (rank = rigid velocities per body) and one term per active contact point. Neglected, as
  // in jacobian() up to round-off: the q-dependence of M(q) and the velocity-quadratic
  // forces in the elastic columns (first order in q and w; the Newton matrix may be
  // approximate).
  bool structuredJacobian(double t, const double* y, const double* scale,
                          StructuredJacobian& J) override;
  // Contact forces at y (generalised, per body) and the pairs' diagnostics (contact_pair.h).
  void contactForces(const double* y, std::vector<Eigen::VectorXd>& h,
                     std::vector<ContactState>* states);
  SystemEnergies energies(const double* y);
  // Total linear and angular momentum (about the inertial origin), inertial components.
  void momentum(const double* y, Eigen::Vector3d& linear, Eigen::Vector3d& angular) const;

 private:
  std::vector<std::unique_ptr<BodyModel>> bodies_;
  std::vector<std::unique_ptr<ContactPair>> contacts_;
  std::vector<int> pos_offset_, vel_offset_;
  int size_ = 0;
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
  std::vector<Eigen::VectorXd> h_;  // workspace: generalised applied forces per body
  std::vector<ContactState> rhs_states_;
  void layout();
  // Difference quotients of body b's rates (position rates and accelerations, the contact
  // forces in h_ frozen) with respect to its first npCols positions and nvCols velocities:
  // column(j, d positionRates / d y_j, d accelerations / d y_j) for each state index j.
  // Increments sqrt(eps) max(|y_j|, scale_j); yy is restored.
  void rateQuotients(
      int b, int npCols, int nvCols, Eigen::VectorXd& yy, const double* scale,
      const std::function<void(int, const Eigen::VectorXd&, const Eigen::VectorXd&)>& column) const;
};

}  // namespace ffriga
