// Penalty contact of a body's collocated contact surface (paper Sect. 4, Eq. 16-18) against
// a target: what every contact pair of the system has in common, whatever its target is.
//   * ContactPair (runtime/contact/contact_pair.h): two flexible NURBS contact surfaces,
//     each collocated against the other (the paper's pairs);
//   * ObstacleContact (runtime/contact/obstacle_contact.h): one body's contact surface
//     against a rigid obstacle fixed in space (a plane, a sphere), evaluated exactly.
// Each is a force element with stiffness terms (runtime/forces/force_element.h); the
// multibody system holds them as its contact pairs (numContacts, contact(c)), the result
// file gives each a group, and the run stops on what they cannot represent.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "runtime/contact/contact_pressure.h"
#include "runtime/contact/coulomb_friction.h"
#include "runtime/forces/force_element.h"

namespace ffriga {

// Diagnostics of one pair at one state (a ContactPair averages them over its two roles).
struct ContactState {
  double normal_force = 0.0;  // N, magnitude of the resultant normal contact force on body A
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // N, resultant on body A, inertial
                                                    // (axisymmetric: (0, F_y, 0), the ring)
  double max_penetration = 0.0;                     // m, largest -g_n over both roles (0 if apart)
  int active_points = 0;                            // collocation points with g_n < 0, both roles
  double energy = 0.0;          // J, penalty energy sum 1/2 c_p g_n^2 w_i, averaged
  int projection_failures = 0;  // closest-point searches that did not converge
  // m: the deepest penetration the pair cannot represent: a collocation point near the
  // target whose closest point is on the edge of the target's contact surface (beyond it)
  // while the point is behind the surface's tangent planes at that edge point and at the
  // surface's centre (ContactPair::beyondEdgeDepth). Such a point is inside the target body
  // but gets no force: the contact region is too small for the motion (0 while every
  // penetrating point has a proper foot point).
  double beyond_edge_penetration = 0.0;
  // Friction (pairs with a friction coefficient; runtime/contact/coulomb_friction.h): the
  // tangential part of `force` (N, inertial), the power the friction takes out (W >= 0),
  // the active points that stick (|v_t| < eps) and slip.
  Eigen::Vector3d tangential_force = Eigen::Vector3d::Zero();
  double friction_power = 0.0;
  int sticking_points = 0, slipping_points = 0;
};

// The deepest initial penetration of a pair (SurfaceContact::deepestPenetration).
struct Penetration {
  double depth = 0.0;  // m, largest -g_n, 0 if none
  int contact_body = -1;  // system index of the body whose collocation point it is
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // that point, world coordinates (m)
};

struct ContactOptions {
  double penalty = 0.0;         // c_p, N/m^3
  bool both_roles = true;       // average A->B and B->A (paper); else A is the contact body
                                // (an obstacle pair has one role: the body's)
  double search_margin = -1.0;  // m; < 0: 10 % of the larger surface's bounding box size
  // m; < 0: 1e-6 of the larger surface's size (the initial penetration accepted, and the
  // penetration beyond a surface's edge that stops a run)
  double penetration_tolerance = -1.0;
  // m; < 0: 1e-3 of the larger surface's size. How far beyond the edge of a planar target
  // contact surface a collocation point may lie (laterally, off the surface) and still be
  // held by the tangent plane at the edge (ContactPair::searchPoint): flat faces of equal
  // size meeting end-on (rods) put their edge points on each other's edges, where the
  // faces' slightly different lateral strains move a point just off the other face. Curved
  // targets have none (their region's edge is where a growing contact must stop the run).
  double edge_reach = -1.0;
  // Coulomb friction (default none: frictionless, bit for bit as before friction existed).
  FrictionLaw friction;
};

class SurfaceContact : public ForceElement {
 public:
  // a, b: the system indices of the two bodies; b = -1: the target is fixed in space.
  SurfaceContact(std::string name, int a, int b, const ContactOptions& options)
      : ForceElement(std::move(name), a, b), options_(options) {}

  const ContactOptions& options() const { return options_; }
  const char* kind() const override { return "contact"; }
  bool isContact() const override { return true; }
  bool hasStiffnessTerms() const override { return true; }
  // The name of the target in reports when it is not a body (b = -1): the obstacle's.
  const std::string& obstacleName() const { return obstacle_name_; }
  // The contact region (SID contact surface) of side 0 (body A) or 1 (body B; "" for an
  // obstacle).
  virtual const std::string& regionName(int side) const = 0;

  // A lower bound of the distance between the contact surface(s) and the target at the
  // context's state (m; <= 0 when they may touch): the approach control's gap.
  virtual double boxGap(const ForceContext& at) const = 0;
  // The size of the (larger) contact surface, the diagonal of its undeformed box (m).
  double surfaceSize() const { return size_; }
  double penetrationTolerance() const {
    return options_.penetration_tolerance > 0.0 ? options_.penetration_tolerance : 1e-6 * size_;
  }
  double edgeReach() const {
    return options_.edge_reach >= 0.0 ? options_.edge_reach : 1e-3 * size_;
  }
  // The deepest penetration over every collocation point, without any pre-check (a full
  // search per point: for the initial state, not for every step).
  virtual Penetration deepestPenetration(const ForceContext& at) const = 0;

  // Counts of the closest-point searches: done, and avoided by a clearance bound.
  long long searches() const { return searches_; }
  long long searchesAvoided() const { return avoided_; }
  // The pressure at every collocation point of each role in the last evaluation that filled
  // a ContactState (the right-hand sides': the simulation reads their states), recorded in
  // the serial sums of the points (O(points) per evaluation; the result file keeps it at each
  // pair's force peak, runtime/output/peak_contact_pressure.h).
  const ContactPressure& pressureField() const { return pressure_; }

  // Stick anchors (friction with `anchored`, runtime/contact/coulomb_friction.h
  // AnchoredFriction): the number of state entries the pair adds (d per collocation point;
  // 0 without); their values at the context's state with every point's anchor on the point
  // (the initial state); the same for the points out of contact only (the projection after
  // every step: an anchor out of contact rests, dz/dt = 0, and is put back on its point
  // between steps, so that a point enters contact with its anchor on it); and from the last
  // evaluation the anchors' rates.
  virtual int numAnchors() const { return 0; }
  virtual void initialAnchors(const ForceContext& at, double* z) const {
    (void)at;
    (void)z;
  }
  virtual void followAnchors(const ForceContext& at, double* z) const {
    (void)at;
    (void)z;
  }
  const Eigen::VectorXd& anchorRates() const { return anchor_rates_; }
  // The quasi-static projection's Newton iteration with anchored friction (FrictionBranch):
  // while held, each point keeps the branch of its first evaluation after
  // holdFrictionBranches(true), a slipping one with its anchor on the slip limit along its
  // slip direction of then. releaseExceeded() turns the sticking points whose spring now
  // exceeds mu f_n (in the last evaluation) to slip, true if any (the projection then
  // iterates again); settleAnchors puts the slipping points' anchors on their slip limit
  // along the held direction at the context's state (z: the pair's anchors), where the
  // law's two branches agree and give the force the iteration held.
  void holdFrictionBranches(bool hold) {
    hold_branches_ = hold;
    branches_.clear();
  }
  virtual bool releaseExceeded() { return false; }
  virtual void settleAnchors(const ForceContext& at, double* z) const {
    (void)at;
    (void)z;
  }

 protected:
  Eigen::VectorXd anchor_rates_;
  bool hold_branches_ = false;
  // Per collocation point while held: not evaluated yet, sticking, slipping with its anchor
  // on the slip limit (FrictionBranch::kFollow), sticking with the spring beyond the limit in
  // the last evaluation (releaseExceeded turns it to slip); the slip directions (d per point).
  enum class HeldBranch : char { kUnset, kStick, kSlip, kStickExceeded };
  std::vector<HeldBranch> branches_;
  Eigen::VectorXd held_directions_;
  ContactOptions options_;
  std::string obstacle_name_;
  double size_ = 0.0;
  long long searches_ = 0, avoided_ = 0;
  ContactPressure pressure_;
};

}  // namespace ffriga
