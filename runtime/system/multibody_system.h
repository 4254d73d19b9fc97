// The multibody system: any number of flexible, frozen or rigid bodies
// (runtime/bodies/body_model.h), gravity, contact pairs (runtime/contact/contact_pair.h),
// force elements along lines (runtime/forces/line_force.h) and joints
// (runtime/constraints/joint.h), in first-order form for the integrator (paper Eq. 1 for
// every body):
//
//   y = [s_p(body 0), s_p(body 1), ..., s_v(body 0), s_v(body 1), ...],
//   dy/dt = [position rates; accelerations from M(q) dz = h_d + h_b - h_omega - h_e + J^T lambda].
//
// Force elements (runtime/forces/force_element.h: contact pairs, spring-dampers, Hertz point
// contact) are the discrete forces h_d (Eq. 18); each adds equal and opposite forces to its
// two bodies, in the order they were added.
//
// Joints (system/constrained_motion.cc). The constraints g(s_p) = 0 are imposed at the
// acceleration level, J dz/dt + bias = 0, with multipliers lambda found in every right-hand
// side by a Schur complement on the bodies' own mass solves:
//   a_b = M_b^-1 h_b (unconstrained),  X_b = M_b^-1 J_b^T,  S = sum_b J_b X_b  (m x m, SPD),
//   S lambda = -bias - sum_b J_b a_b,   dz_b/dt = a_b + X_b lambda.
// Why this and not IDA or relative coordinates: the bodies keep their O(nq) mass solves
// (Me = E), the integrator keeps seeing an ODE (CVODE's BDF, as for free bodies), closed
// loops need nothing special, and the drift of the position and velocity constraints that
// the acceleration form allows is removed by CVODE's projection after every step
// (CVodeSetProjFn; project() below):
//   positions:  dz = -X_r S_r^-1 g, s_p <- s_p + (ds_p/dz) dz  (Newton, to |g| <= 1e-13)
//               with X_r = M_r^-1 J_r^T over the rigid coordinates only, M_r the bodies'
//               rigid mass blocks: a correction in the full mass metric would move mostly
//               the light, stiff constraint modes at the joints' markers and pump energy
//               into them at every step (seen: a swinging flexible rod's reactions grew
//               a hundredfold in 50 ms). Where the rigid motion cannot close the joints
//               (S_r singular) the full mass metric X = M^-1 J^T serves;
//   velocities: z_r <- z_r - X_r S_r^-1 J z, likewise by the rigid velocities (a correction
//               in the full mass metric kicks the same modes' velocities at every step;
//               seen: undamped 20-90 kHz rod modes growing until they set the step).
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "runtime/bodies/body_model.h"
#include "runtime/constraints/joint.h"
#include "runtime/contact/surface_contact.h"
#include "runtime/forces/line_force.h"
#include "runtime/integration/ode_system.h"

namespace ffriga {

struct SystemEnergies {
  double kinetic = 0.0;         // J
  double elastic = 0.0;         // J, 1/2 q^T Ke q summed over bodies
  double gravity = 0.0;         // J, potential of gravity
  double contact = 0.0;         // J, penalty energy of the active contact points
  double force_elements = 0.0;  // J, potential energy of the force elements (springs, Hertz)
};

// A marker whose inertial position and velocity the result file records: on a 3D, rigid
// or frozen body (end.model set) or on an axisymmetric one (end.model null; its marker in
// the meridian plane, world z = 0).
struct Sensor {
  std::string name;
  MarkerEnd end;
};

// All joint equations at one state, over the system's velocities (columns: body b's
// velocities start at velocityOffset(b) - velocityOffset(0)).
struct ConstraintRows {
  Eigen::VectorXd g, bias;  // m
  Eigen::MatrixXd J;        // m x (total velocities)
  std::vector<JointRows> joints;
};

class MultibodySystem : public OdeSystem {
 public:
  int addBody(std::unique_ptr<BodyModel> body);  // returns the body's index
  // A force element of any kind (a contact pair, a line force); its slot among its kind.
  void addForceElement(std::unique_ptr<ForceElement> element);
  void addJoint(std::unique_ptr<Joint> joint);
  void addSensor(Sensor sensor) { sensors_.push_back(std::move(sensor)); }
  int numSensors() const { return static_cast<int>(sensors_.size()); }
  const Sensor& sensor(int s) const { return sensors_[s]; }
  // Inertial position (m) and velocity (m/s) of sensor s at y.
  void sensorState(const double* y, int s, Eigen::Vector3d& position,
                   Eigen::Vector3d& velocity) const;
  void setGravity(const Eigen::Vector3d& g) { gravity_ = g; }
  const Eigen::Vector3d& gravity() const { return gravity_; }

  int numBodies() const { return static_cast<int>(bodies_.size()); }
  const BodyModel& body(int b) const { return *bodies_[b]; }
  BodyModel& body(int b) { return *bodies_[b]; }
  int numForceElements() const { return static_cast<int>(forces_.size()); }
  const ForceElement& forceElement(int i) const { return *forces_[i]; }
  // The force elements by kind: contact pairs, line forces (each in the order added).
  int numContacts() const { return static_cast<int>(contacts_.size()); }
  const SurfaceContact& contact(int c) const { return *contacts_[c]; }
  SurfaceContact& contact(int c) { return *contacts_[c]; }
  // The name of contact pair c's side 0 (body A) or 1 (body B, or the obstacle).
  const std::string& contactSideName(int c, int side) const;

  int numJoints() const { return static_cast<int>(joints_.size()); }
  const Joint& joint(int j) const { return *joints_[j]; }
  Joint& joint(int j) { return *joints_[j]; }
  int numConstraints() const { return num_constraints_; }
  int numLineForces() const { return static_cast<int>(line_forces_.size()); }
  const LineForce& lineForce(int f) const { return *line_forces_[f]; }

  int size() const override { return size_; }
  int positionOffset(int b) const { return pos_offset_[b]; }
  int velocityOffset(int b) const { return vel_offset_[b]; }
  // The stick anchors of contact pair c (SurfaceContact::numAnchors entries, world
  // coordinates; runtime/contact/coulomb_friction.h) start at anchorOffset(c), after every
  // body's velocities: y = [positions, velocities, anchors of pair 0, pair 1, ...].
  int anchorOffset(int c) const { return anchor_offset_[c]; }
  // Sets the anchors in y (positions set) on their points: the initial state's.
  void placeAnchors(double* y) const;
  bool hasAnchors() const {
    return size_ > num_velocities_ + (bodies_.empty() ? 0 : vel_offset_[0]);
  }

  void rhs(double t, const double* y, double* ydot) override;
  void normalize(double* y) const override;
  bool hasConstraints() const override {
    return !joints_.empty() || hasQuasiStatic() || hasAnchors();
  }
  // True if any body has quasi-static coordinates (runtime/bodies/quasi_static_modes.h).
  bool hasQuasiStatic() const;
  // Moves the quasi-static coordinates onto their manifold a_s(y) = 0
  // (runtime/system/quasi_static_projection.cc); false if Newton's iteration did not converge.
  bool projectQuasiStatic(double* y);
  // CVODE's projection: corr = P(y) - y with P the projection of the header comment.
  // Returns false if Newton's iteration on the positions did not converge.
  bool project(double t, const double* y, double* corr) override;
  // Projects y itself (joints: positions, then velocities; then the quasi-static
  // coordinates; then the anchors of the points out of contact onto their points); false if
  // not converged.
  bool projectState(double* y);
  // Moves only the rigid positions and velocities (elastic coordinates held) until the
  // joints close (runtime/system/static_preload.h).
  bool projectStateRigidly(double* y);
  // The joint equations at y.
  void constraintRows(const double* y, ConstraintRows& rows) const;
  // X = M^-1 J^T over the bodies (rows of the system's velocities; J over them).
  void inverseMassTimes(const double* y, const Eigen::MatrixXd& J, Eigen::MatrixXd& X) const;
  // Multipliers at y (one right-hand side), per joint its reaction on end b
  // (runtime/constraints/joint.h).
  std::vector<JointReaction> jointReactions(const double* y);
  // The force elements' states at y.
  std::vector<LineForceState> lineForceStates(const double* y) const;
  // True if anything in the system dissipates energy: a body's modal damping De != 0, a
  // force element with a damper, or a contact pair with friction.
  bool dissipates() const;
  // True if a contact pair has friction (runtime/contact/coulomb_friction.h).
  bool hasFriction() const;
  // The power (W) that modal damping (qdot^T De qdot of each body) and the force elements'
  // dampers take out of the system at y; with the friction's power (ContactState::
  // friction_power, from the right-hand sides) its time integral is the result's
  // /energy/dissipated (runtime/simulation/simulation.cc).
  double dissipationPower(const double* y) const;
  // Newton-matrix Jacobian: difference quotients of each body's own rates with the contact
  // forces frozen (cheap: no contact search), plus the analytic low-rank contact stiffness
  // (contact_pair.h) mapped by M(q)^-1.
  bool jacobian(double t, const double* y, const double* f, const double* scale,
                double* J) override;

  // The pairs' diagnostics at the state of the latest rhs() call. CVODE evaluates the
  // right-hand side last at the final Newton iterate of an accepted step, so after a step
  // this is the contact state at its end to within the Newton tolerance, at no extra cost.
  const std::vector<ContactState>& lastRhsContacts() const { return rhs_states_; }
  // The force elements' states at the same moment.
  const std::vector<LineForceState>& lastRhsLineForces() const { return rhs_line_states_; }
  // The same Jacobian in structured form (runtime/integration/structured_newton.h), available when
  // every body has Me = E and diagonal Ke, De: D holds the elastic pairs; U V^T the rigid columns
  // (difference quotients as above), the rigid-elastic inertial coupling through M(q)^-1
  // (rank = rigid velocities per body) and one term per active contact point. Neglected, as
  // in jacobian() up to round-off: the q-dependence of M(q) and the velocity-quadratic
  // forces in the elastic columns (first order in q and w; the Newton matrix may be
  // approximate). With joints the rigid columns are quotients of the constrained rates of
  // all bodies, the other columns are projected onto the constrained motion and each joint
  // equation adds one column (projectJacobian); force elements need joints here (their
  // stiffness then enters through the rigid columns only).
  bool structuredJacobian(double t, const double* y, const double* scale,
                          StructuredJacobian& J) override;
  // The generalised forces at y (per body, from zero) of the force elements with stiffness
  // terms (the contact pairs, held fixed in difference quotients) and the pairs' diagnostics
  // (contact_pair.h).
  void contactForces(const double* y, std::vector<Eigen::VectorXd>& h,
                     std::vector<ContactState>* states);
  SystemEnergies energies(const double* y);
  // The smallest bounding-box gap of the contact pairs at y (SurfaceContact::boxGap, m;
  // +infinity without pairs) and the size of that pair's surfaces (m).
  double contactGap(const double* y, double* size = nullptr) const;
  // The deepest penetration of contact pair c at y (SurfaceContact::deepestPenetration).
  Penetration deepestPenetration(const double* y, int c) const;
  // Total linear and angular momentum (about the inertial origin), inertial components.
  void momentum(const double* y, Eigen::Vector3d& linear, Eigen::Vector3d& angular) const;

 private:
  std::vector<std::unique_ptr<BodyModel>> bodies_;
  std::vector<std::unique_ptr<ForceElement>> forces_;  // in the order added
  std::vector<SurfaceContact*> contacts_;              // the contact pairs among them
  std::vector<std::unique_ptr<Joint>> joints_;
  std::vector<LineForce*> line_forces_;                // the line forces among them
  std::vector<Sensor> sensors_;
  int num_constraints_ = 0;
  Eigen::VectorXd lambda_;  // multipliers of the latest rhs()
  std::vector<int> pos_offset_, vel_offset_, anchor_offset_;
  int size_ = 0;
  int num_velocities_ = 0;  // of all bodies
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
  std::vector<Eigen::VectorXd> h_;  // workspace: generalised applied forces per body
  std::vector<ContactState> rhs_states_;
  std::vector<LineForceState> rhs_line_states_;
  void layout();
  // dy/dt at y; the contact pairs' diagnostics into `states` if given.
  // = constrainedAccelerations, then each body's quasi-static rates (QuasiStaticModes::apply).
  void evaluateRates(const double* y, double* ydot, std::vector<ContactState>* states,
                     std::vector<LineForceState>* lineStates);
  // dy/dt at y before the quasi-static coordinates' rates: position rates, and the
  // accelerations a = M^-1 (h + J^T lambda) of every coordinate, quasi-static ones included
  // (their a_s is what the relaxation and the projection drive to zero).
  void constrainedAccelerations(const double* y, double* ydot, std::vector<ContactState>* states,
                                std::vector<LineForceState>* lineStates);
  int totalVelocities() const { return num_velocities_; }
  // The dense Jacobian's anchor entries (jacobian()): the terms' columns on the anchors and
  // the anchors' rows.
  void denseAnchorTerms(const double* y, Eigen::Map<Eigen::MatrixXd>& J);
  // The anchors' rates of the last contactForces() into ydot.
  void anchorRates(double* ydot) const;
  // Calls (pair.*place)(the state y, the pair's anchors in y) for every pair with anchors:
  // SurfaceContact::initialAnchors, followAnchors or settleAnchors.
  void placeEachPairsAnchors(double* y, void (SurfaceContact::*place)(const ForceContext&, double*)
                                            const) const;
  // Adds the generalised forces at y of the force elements without stiffness terms (line
  // forces, evaluated in difference quotients) to h (states: optional diagnostics).
  void addLineForces(const double* y, std::vector<Eigen::VectorXd>& h,
                     std::vector<LineForceState>* states) const;
  // Whether some force element has no stiffness terms (its stiffness only through difference
  // quotients of the rates).
  bool hasQuotientForces() const;
  // X = M^-1 J^T (inverseMassTimes) and the factor of S = J X; ComputeError if singular.
  void constraintMobility(const double* y, const Eigen::MatrixXd& J, Eigen::MatrixXd& X,
                          Eigen::LLT<Eigen::MatrixXd>& S) const;
  // Adds X lambda to the accelerations in ydot, lambda solving the header's Schur system.
  void applyConstraints(const double* y, double* ydot);
  // Newton steps on the position constraints, dz = -X S^-1 g, then the velocities,
  // z <- z - X S^-1 J z, with X = M^-1 J^T or, rigidOnly, X = M_r^-1 J_r^T over the rigid
  // velocity columns (elastic coordinates and velocities held). False if the positions do
  // not converge to |g| <= 1e-13 or (rigidOnly) the rigid motion cannot close the joints.
  bool closeConstraints(double* y, bool rigidOnly);
  bool projectionMobility(const double* y, const ConstraintRows& rows, bool rigidOnly,
                          Eigen::MatrixXd& X, Eigen::LLT<Eigen::MatrixXd>& S) const;
  // Difference quotients of body b's rates (position rates and accelerations, the contact
  // forces in h_ frozen) with respect to its first npCols positions and nvCols velocities:
  // column(j, d positionRates / d y_j, d accelerations / d y_j) for each state index j.
  // Increments sqrt(eps) max(|y_j|, scale_j); yy is restored.
  void rateQuotients(
      int b, int npCols, int nvCols, Eigen::VectorXd& yy, const double* scale,
      const std::function<void(int, const Eigen::VectorXd&, const Eigen::VectorXd&)>& column) const;
  // With joints: difference quotients of the whole system's rates (contact forces in h_
  // frozen; force elements and constraint forces evaluated) for body b's first npCols
  // positions and nvCols velocities: column(j, d f / d y_j) over all n rows.
  void constrainedQuotients(int b, int npCols, int nvCols, Eigen::VectorXd& yy, const double* scale,
                            const std::function<void(int, const Eigen::VectorXd&)>& column);
  // With joints: projects the structured Jacobian's columns onto the constrained motion and
  // appends the joints' num_constraints_ columns at col (multibody_system.cc).
  void projectJacobian(const double* y, StructuredJacobian& J, int& col) const;
  // The phases of structuredJacobian(). The number of its low-rank columns: per body the
  // rigid positions and twice the rigid velocities, one per contact stiffness term and one
  // per joint equation.
  int structuredRank() const;
  // Body b's elastic pairs, d/dt q = qdot, d/dt qdot = -k q - c qdot (Me = E), appended to
  // J's q_index, v_index, k and c; its quasi-static coordinates, d/dt q = -q / tau + ...,
  // to J.f_index and fRate (their rows of U are transformed afterwards).
  void elasticPairs(int b, StructuredJacobian& J, std::vector<double>& fRate) const;
  // Body b's rigid columns of U V^T from column col on: difference quotients of the body's
  // rates, contact forces frozen (with joints: of every body's constrained rates, which the
  // joints couple).
  void rigidColumns(int b, Eigen::VectorXd& yy, const double* scale, StructuredJacobian& J,
                    int& col);
  // Body b's rigid-elastic inertial coupling, nrv columns from col on, through
  // M^-1 = [[S^-1, -S^-1 C^T], [-C S^-1, E + C S^-1 C^T]] (S = Mrr - C^T C):
  // d a / d(q, qdot) = [0; -(k, c)] + [I; -C] S^-1 C^T (k, c). C and Sinv = S^-1 are kept
  // for contactColumns().
  void inertialCouplingColumns(int b, const double* y, StructuredJacobian& J, Eigen::MatrixXd& C,
                               Eigen::MatrixXd& Sinv, int& col) const;
  // One column per contact stiffness term from col on: d h / d s_p = -k [bvC; -bvT]
  // [bpC; -bpT]^T (contact_pair.h), mapped by each body's M^-1 (its C and Sinv).
  void contactColumns(const std::vector<Eigen::MatrixXd>& C,
                      const std::vector<Eigen::MatrixXd>& Sinv, StructuredJacobian& J,
                      int& col) const;
  // A step of projectQuasiStatic(): the contact and force elements' forces at y into h_ and
  // the accelerations of each body with quasi-static coordinates (first[b] >= 0) into accel[b]
  // (with joints the constrained ones, constrainedAccelerations).
  void quasiStaticAccelerations(const double* y, const std::vector<int>& first,
                                std::vector<Eigen::VectorXd>& accel);
};

}  // namespace ffriga
