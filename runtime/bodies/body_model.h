// One flexible body in the floating frame of reference (paper Sect. 2, Eq. 1), as the
// multibody system sees it: its share of the state, its kinematics and its accelerations
// under applied generalised forces.
//
// State of a body: positions s_p (rigid positions, then q) and velocities s_v (rigid
// velocities, then qdot). Generalised forces h have the layout of s_v: rigid part first
// (numRigidVelocities entries), then the nq elastic entries.
//
// Two kinds (bodies of different kinds are not combined in one scene):
//   * FloatingBody3d: s_p = [r_R (3, inertial, m), p (unit quaternion)],
//                     s_v = [v (3, body components, m/s), w (3, body components, rad/s)].
//   * AxisymmetricBody (2D SID data): translation along the common axis, the inertial y axis:
//                     s_p = [Y (m)], s_v = [V (m/s)]; contact geometry in the meridian plane
//                     (radius, y).
// A material point with body coordinates x (deformed, x = x0 + u) is at
//   world = origin + A x
// in the contact space (3D, or the meridian plane for axisymmetric bodies).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "common/sid/sid.h"
#include "runtime/bodies/quasi_static_modes.h"
#include "runtime/bodies/space_vector.h"

namespace ffriga {

struct BodyPose {
  Eigen::MatrixXd A;       // d x d, body -> world components
  Eigen::VectorXd origin;  // d, m
  Eigen::VectorXd q;       // nq elastic coordinates
};

class BodyModel {
 public:
  BodyModel(std::string name, std::shared_ptr<const FlexibleBodySid> sid);
  virtual ~BodyModel() = default;

  const std::string& name() const { return name_; }
  const FlexibleBodySid& sid() const { return *sid_; }
  const std::shared_ptr<const FlexibleBodySid>& sharedSid() const { return sid_; }
  int nq() const { return sid_->nq(); }
  int spaceDim() const { return sid_->space_dim; }
  virtual int numRigidPositions() const = 0;
  virtual int numRigidVelocities() const = 0;
  int numPositions() const { return numRigidPositions() + nq(); }
  int numVelocities() const { return numRigidVelocities() + nq(); }

  // Modal damping De (nq x nq), initially the SID's; a scene may override it.
  const Eigen::MatrixXd& damping() const { return De_; }
  void setDamping(const Eigen::MatrixXd& De);

  // Quasi-static elastic coordinates (runtime/bodies/quasi_static_modes.h): those with
  // frequency >= cutoff_hz; none before the first call. Throws InputError unless Me = E and
  // Ke is diagonal (diagonalElasticity()).
  void setQuasiStatic(double cutoff_hz);
  // Gives the listed elastic coordinates back their inertia (joints: jointHeldCoordinates).
  void keepDynamic(const std::vector<int>& coordinates) { qs_ = qs_.without(coordinates); }
  const QuasiStaticModes& quasiStatic() const { return qs_; }
  // Applies the quasi-static coordinates' rates to the body's rates (positionRates() into
  // spdot, accelerations() into accel; QuasiStaticModes::apply).
  void applyQuasiStatic(double* spdot, double* accel) const {
    if (!qs_.empty()) qs_.apply(numRigidPositions(), numRigidVelocities(), spdot, accel);
  }

  // Structure for the Newton matrix (runtime/integration/structured_newton.h). True if Me = E and
  // Ke, De are diagonal (Eq. 13; to 1e-8 relative: the Newton matrix may be approximate), with
  // their diagonals k (1/s^2) and c (1/s).
  bool diagonalElasticity() const { return diagonal_; }
  const Eigen::VectorXd& stiffnessDiagonal() const { return k_; }
  const Eigen::VectorXd& dampingDiagonal() const { return c_; }
  // The mass matrix M(q) = [[Mrr, C^T], [C, Me]] split at the rigid velocities: C is
  // nq x numRigidVelocities(), Mrr square.
  virtual void massBlocks(const double* sp, Eigen::MatrixXd& C, Eigen::MatrixXd& Mrr) const = 0;

  virtual BodyPose pose(const double* sp) const = 0;
  // d s_p / dt from (s_p, s_v).
  virtual void positionRates(const double* sp, const double* sv, double* spdot) const = 0;
  // d s_v / dt: solves M(q) dz = h_applied + h_gravity - h_omega - h_e (Eq. 1).
  // `gravity`: inertial acceleration of gravity (3, m/s^2).
  virtual void accelerations(const double* sp, const double* sv, const double* h_applied,
                             const Eigen::Vector3d& gravity, double* accel) const = 0;
  // Solves M(q) X = B in place (B: numVelocities() rows, any number of columns).
  virtual void solveMass(const double* sp, Eigen::MatrixXd& B) const = 0;
  // Velocity-space and position-space gradients of a world point's position for the contact
  // stiffness: for the material point x (deformed, body frame) with modes Phi_x (d x nq) and
  // a world direction n (d): bv = G_v^T n (numVelocities; the generalised force of a unit
  // force along n) and bp = (dx_world/ds_p)^T n (numPositions; rotation parameters left 0).
  virtual void pointGradients(const BodyPose& pose, const VectorRef& x,
                              const Eigen::MatrixXd& Phi_x, const VectorRef& n, Eigen::VectorXd& bv,
                              Eigen::VectorXd& bp) const = 0;
  // The world velocity (d components, m/s) of the material point at x (deformed, body
  // frame) whose elastic velocity in the body frame is u_dot (d, Phi_x qdot), at the
  // velocities sv: G_v^T sv of pointGradients' bv along the world axes, without forming them.
  virtual Eigen::VectorXd pointVelocity(const BodyPose& pose, const double* sv, const VectorRef& x,
                                        const VectorRef& u_dot) const = 0;
  // Adds the rigid part of the generalised force of a world force f (d components, N) acting
  // at body point x (d, deformed, m): translational and rotational parts of Eq. (18).
  virtual void addRigidPointForce(const BodyPose& pose, const VectorRef& x, const VectorRef& f,
                                  double* h) const = 0;

  // Kinetic energy 1/2 z^T M(q) z (J), elastic energy 1/2 q^T Ke q (J), potential energy
  // of gravity -g . (m r_R + A m c(q)) (J).
  virtual double kineticEnergy(const double* sp, const double* sv) const = 0;
  double elasticEnergy(const double* sp) const;
  virtual double gravityEnergy(const double* sp, const Eigen::Vector3d& gravity) const = 0;
  // Linear (kg m/s) and angular momentum about the inertial origin (kg m^2/s), inertial
  // components (axisymmetric: linear along y only, angular zero).
  virtual void momentum(const double* sp, const double* sv, Eigen::Vector3d& linear,
                        Eigen::Vector3d& angular) const = 0;
  // Normalises what the state keeps normalised (the quaternion).
  virtual void normalize(double* sp) const { (void)sp; }

 protected:
  std::string name_;
  std::shared_ptr<const FlexibleBodySid> sid_;
  Eigen::MatrixXd De_;
  Eigen::LLT<Eigen::MatrixXd> Me_llt_;  // factor of Me
  bool diagonal_ = false;               // to 1e-8: for the Newton matrix
  bool exactly_diagonal_ = false;       // Me = E, Ke, De diagonal exactly (igaprep's SIDs): the
                                        // right-hand side may use k_, c_ in O(nq)
  Eigen::VectorXd k_, c_;
  QuasiStaticModes qs_;

 private:
  void checkDiagonal();
};

}  // namespace ffriga
