// Force elements (DESIGN.md "Multibody"): all that applies equal and opposite discrete
// forces h_d (paper Eq. 1, 18) to two bodies, or to a body and the ground, as a function of
// their state: the contact pairs between NURBS surfaces (runtime/contact/contact_pair.h)
// and the line forces between two markers, spring-dampers and Hertz point contact
// (runtime/forces/line_force.h). The multibody system holds them in one list, in the order
// the scene adds them, and sums their forces in that order.
//
// Their stiffness enters the Newton matrix in one of two ways:
//   * an element with stiffness terms (contact pairs) hands its linearisation as low-rank
//     terms, d h / d s_p = -k [bvA; -bvB] [bpA; -bpB]^T per term (StiffnessTerm), and is held
//     fixed in the difference quotients of the bodies' rates;
//   * the others (line forces) are evaluated at every perturbed state of those quotients.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "runtime/bodies/body_model.h"

namespace ffriga {

struct ContactState;    // runtime/contact/contact_pair.h
struct LineForceState;  // runtime/forces/line_force.h

// Linearisation of one force along a direction n between a point of body_c and a point of
// body_t (Eq. 17-18, a contact pair's active collocation point): with g = n^T (x_C - x_T),
// h_C = bvC phi, h_T = -bvT phi, phi = -k g:  d h / d s_p = -k [bvC; -bvT] [bpC; -bpT]^T
// (change of n neglected). k in N/m. Friction (runtime/contact/coulomb_friction.h) adds
// terms of the same form: its damping along a tangent t, d h / d s_v = -c [bvC; -bvT]
// [bvC; -bvT]^T with bp = bv (the point's velocity along t is bv^T s_v; k = c in N s/m), and
// its dependence on the normal force, d h / d s_p with bv along the friction force's
// direction and bp along the normal.
struct StiffnessTerm {
  enum class Kind {
    kNormal,           // the penalty's symmetric normal stiffness (d/d s_p)
    kFrictionLoad,     // friction through the normal force (d/d s_p; not symmetric)
    kFrictionDamping,  // friction's velocity dependence (d/d s_v)
  };
  int body_c = 0, body_t = 0;  // system body indices
  double k = 0.0;              // N/m (kFrictionDamping: N s/m)
  Eigen::VectorXd bvC, bpC, bvT, bpT;
  Kind kind = Kind::kNormal;
  // Friction with stick anchors (runtime/contact/coulomb_friction.h AnchoredFriction): the
  // term's share of the pair's anchors. anchor >= 0: the index of the point's first anchor
  // entry among the pair's; the term's column of the Jacobian is then
  // U = [-k M^-1 [bvC; -bvT]; aU on the anchor's rows], V = [[bpC; -bpT]; aV on its columns].
  int anchor = -1;
  Eigen::VectorXd aU, aV;
  bool onVelocities() const { return kind == Kind::kFrictionDamping; }
};

// The bodies' state at which force elements are evaluated (given by the system).
class ForceContext {
 public:
  virtual ~ForceContext() = default;
  virtual const BodyModel& body(int b) const = 0;
  virtual const double* positions(int b) const = 0;   // s_p of body b
  virtual const double* velocities(int b) const = 0;  // s_v of body b
  virtual const BodyPose& pose(int b) const = 0;      // body b's pose at s_p
  // The stick anchors of contact pair `slot` (runtime/contact/coulomb_friction.h), world
  // coordinates; nullptr where the pair has none.
  virtual const double* anchors(int slot) const {
    (void)slot;
    return nullptr;
  }
};

// Where the elements of each kind leave their diagnostics, at their slot (the index among
// the elements of their kind); nullptr: not wanted.
struct ForceStates {
  std::vector<ContactState>* contacts = nullptr;
  std::vector<LineForceState>* line_forces = nullptr;
};

class ForceElement {
 public:
  // a, b: system indices of the two bodies (a = -1: the ground).
  ForceElement(std::string name, int a, int b) : name_(std::move(name)), bodies_{a, b} {}
  virtual ~ForceElement() = default;

  const std::string& name() const { return name_; }
  int bodyA() const { return bodies_[0]; }
  int bodyB() const { return bodies_[1]; }
  // "contact" (a pair of NURBS surfaces), "spring_damper", "hertz_contact".
  virtual const char* kind() const = 0;
  // Contact laws: a compressive force means contact (the phases of paper Table 3 and the
  // headline contact figures count it).
  virtual bool isContact() const = 0;
  // Its index among the elements of its kind in the system (set when it is added).
  int slot() const { return slot_; }
  void setSlot(int slot) { slot_ = slot; }

  // Adds the generalised forces at the context's state to h (one vector per body, the
  // layout of its velocities; nothing for the ground) and its diagnostics to `states`.
  virtual void addForces(const ForceContext& at, std::vector<Eigen::VectorXd>& h,
                         const ForceStates& states) = 0;
  // True if its stiffness enters as stiffnessTerms() (header comment).
  virtual bool hasStiffnessTerms() const { return false; }
  // The linearisation at the state of the last addForces().
  virtual const std::vector<StiffnessTerm>& stiffnessTerms() const;

 private:
  std::string name_;
  int bodies_[2];
  int slot_ = 0;
};

}  // namespace ffriga
