// Penalty contact of a body's contact surface against a rigid obstacle fixed in space
// (runtime/contact/rigid_obstacle.h): the paper's collocation (Sect. 4) with the target's
// closest point, gap and normal evaluated exactly instead of by Newton on a NURBS surface.
// Every collocation point i of body A (runtime/contact/collocated_surface.h) at
// x_i = origin + A (x0_i + Phi_i q) with g_i = g(x_i) < 0 and its foot point on the
// obstacle carries (Eq. 17)
//   f_i = -c_p g_i w_i n_i,
// and adds A^T f_i, x_i x A^T f_i and Phi_i^T A^T f_i to the body's generalised forces
// (Eq. 18); the obstacle takes the reaction. One role only: the obstacle's surface is exact
// and rigid, so there is nothing to average (ContactOptions::both_roles is not used).
// UNITS: c_p is a pressure per unit penetration, N/m^3: the contact pressure at a point is
// c_p |g|. Against a rigid half-space Hertz's law is that of the body alone
// (E* = E / (1 - nu^2), R* = R), with which the penalty is chosen as for a pair.
// Stiffness terms: one per active point, k = c_p w_i, body_t = -1, from the body's
// pointGradients as for pairs: the change of n is neglected (none for a plane) and so is the
// change of the lever arm under rotation (the rotational rows' (Phi_i dq) x A^T f_i): the
// Newton matrix may be approximate. With a friction coefficient every active point also
// carries the regularised Coulomb force of runtime/contact/coulomb_friction.h at its velocity
// (the obstacle is at rest), with its damping and normal-force terms in the Newton matrix.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "runtime/bodies/body_model.h"
#include "runtime/contact/collocated_surface.h"
#include "runtime/contact/rigid_obstacle.h"
#include "runtime/contact/surface_contact.h"

namespace ffriga {

class ObstacleContact : public SurfaceContact {
 public:
  // Contact surface `surface` of body a (system index) against `obstacle`.
  ObstacleContact(std::string name, int a, const BodyModel& A, int surface,
                  RigidObstacle obstacle, const ContactOptions& options);

  const RigidObstacle& obstacle() const { return obstacle_; }
  void addForces(const ForceContext& at, std::vector<Eigen::VectorXd>& h,
                 const ForceStates& states) override;
  double boxGap(const ForceContext& at) const override;
  const std::string& regionName(int side) const override { return side == 0 ? side_.name : none_; }
  Penetration deepestPenetration(const ForceContext& at) const override;
  const std::vector<StiffnessTerm>& stiffnessTerms() const override;
  // Adds the generalised contact forces on A to hA (layout of A's velocities) and fills
  // `state` if given; sv: A's velocities (needed with friction only); z: the anchors (needed
  // with anchored friction only).
  void evaluate(const BodyModel& A, const BodyPose& pa, double* hA, ContactState* state,
                const double* sv = nullptr, const double* z = nullptr);
  int numAnchors() const override;
  void initialAnchors(const ForceContext& at, double* z) const override;
  void followAnchors(const ForceContext& at, double* z) const override;
  bool releaseExceeded() override;
  void settleAnchors(const ForceContext& at, double* z) const override;
  // The world position of the contact surface's centre and its outward normal there
  // (undeformed surface at `pa`): for the scene's check that the surface faces the obstacle.
  void surfaceCentre(const BodyPose& pa, Eigen::Vector3d& x, Eigen::Vector3d& n) const;

 private:
  // The box of the surface's control points in the world at pa, displaced by u
  // (CollocatedSurface::displacements).
  void worldBox(const BodyPose& pa, const Eigen::VectorXd& u, Eigen::Vector3d& lo,
                Eigen::Vector3d& hi) const;
  Eigen::Vector3d world(const BodyPose& pa, const Eigen::VectorXd& xb) const;

  CollocatedSurface side_;
  const std::string none_;
  RigidObstacle obstacle_;
  int dim_ = 3;
  double margin_ = 0.0;
  // What stiffnessTerms() needs of each active point of the last evaluate().
  struct ActivePoint {
    int i = 0;
    double k = 0.0;
    Eigen::VectorXd xb, n;
    PointFriction friction;     // with friction: the law's values at the point
    AnchoredFriction anchored;  // with anchored friction: its values
    double fn = 0.0;            // N, the normal force
  };
  bool anchored() const { return options_.friction.active() && options_.friction.anchored; }
  // Anchored friction at active point `point` with normal force fn, anchor z (dim_ entries)
  // and world position x: adds the tangential force to f, its figures to s, the anchor's
  // rate to anchor_rates_.
  void addAnchoredFriction(const Eigen::Vector3d& x, const double* z, double fn, Eigen::VectorXd& f,
                           ContactState& s, ActivePoint& point);
  // Puts the anchors on their points (z: the pair's anchors), all or (outOnly) those of the
  // points out of contact.
  void placeAnchors(const ForceContext& at, double* z, bool outOnly) const;
  // The point's friction at its normal force fn (N), with the point's velocity
  // (BodyModel::pointVelocity; udot: the surface control points' elastic velocities,
  // displacements() of qdot): adds the tangential force to f, its figures to s, and keeps
  // the linearisation in `point`.
  void addFriction(const BodyModel& A, const BodyPose& pa, const double* sv,
                   const Eigen::VectorXd& udot, double fn, Eigen::VectorXd& f, ContactState& s,
                   ActivePoint& point) const;
  std::vector<ActivePoint> active_;
  const BodyModel* body_ = nullptr;
  BodyPose pose_;
  mutable std::vector<StiffnessTerm> terms_;
  mutable bool terms_formed_ = true;
};

}  // namespace ffriga
