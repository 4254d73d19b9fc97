// Coulomb friction at a collocation point in contact (issue 28; schemas/contact_friction.md),
// regularised in the slip velocity: with the point's normal force f_n = c_p |g_n| w_i (N),
// its velocity relative to the target v (m/s, world) and the target's unit normal n,
//   v_t = v - (v . n) n,   s = sqrt(|v_t|^2 + eps^2),   f_t = -mu f_n v_t / s,
// so |f_t| < mu f_n always, -> mu f_n in gross slip (|v_t| >> eps: Coulomb's law), and a
// point that sticks creeps at |v_t| = eps |f_t| / (mu f_n) / sqrt(1 - (|f_t| / (mu f_n))^2).
// The law is smooth (no switching, nothing for the integrator to chatter on) and has no
// internal state: the stick is the creep limit eps -> 0, whose error over a contact of
// duration T is a creep displacement of at most about eps T (schemas/contact_friction.md).
// The power it takes out, P = -f_t . v_t = mu f_n |v_t|^2 / s >= 0, is the friction work's
// rate (/energy/dissipated).
//
// Linearisation for the Newton matrix: with e1 = v_t / |v_t| (any unit tangent where
// v_t = 0) and e2 = n x e1 (3D), d f_t / d v = -mu f_n (eps^2 / s^3 e1 e1^T + 1 / s e2 e2^T)
// (the change of n neglected), and d f_t / d f_n = -mu v_t / s.
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Dense>

#include "runtime/forces/force_element.h"

namespace ffriga {

struct FrictionLaw {
  double coefficient = 0.0;    // mu >= 0 (0: frictionless)
  double slip_velocity = 0.0;  // eps, m/s (> 0 when mu > 0; the regularised law's)
  // The stick anchors' law (below) instead of the velocity-regularised one: stick is
  // elastic with the tangential stiffness c_t = c_p per unit area, slip relaxes the anchor
  // within relaxation_time (s).
  bool anchored = false;
  double relaxation_time = 0.0;
  bool active() const { return coefficient > 0.0; }
};

struct PointFriction {
  Eigen::VectorXd force;  // f_t (d components, N): on the contact body's point
  double power = 0.0;     // W >= 0
  bool sticking = false;  // |v_t| < eps
  // Damping coefficients (N s/m) along the unit tangents e1 and e2 (2D: e1 only, c2 = 0),
  // and d f_t / d f_n (d components).
  Eigen::VectorXd e1, e2, load;
  double c1 = 0.0, c2 = 0.0;
};

// Whether the Newton matrix may leave out the point's damping term with coefficient c: below
// kNegligibleDamping times its larger one. In gross slip c1 / c2 = (eps / |v_t|)^2 (1e-10 at
// 0.1 m/s): a term that changes the matrix by less than that relative amount costs a column
// of its low-rank part (runtime/integration/structured_newton.h: O(n r^2)) for nothing.
constexpr double kNegligibleDamping = 1e-8;
inline bool negligibleDamping(const PointFriction& f, double c) {
  return c < kNegligibleDamping * (f.c1 > f.c2 ? f.c1 : f.c2);
}

// The Newton-matrix terms of a point's friction f beside its normal term `normal`
// (runtime/forces/force_element.h): the damping c1, c2 along e1, e2 on the velocities
// (kFrictionDamping, bp = bv; left out where negligibleDamping), and the normal force's share
// (kFrictionLoad with the normal term's k and bp) along d f_t / d f_n. gradients(e, t) sets
// t.bvC, and t.bvT where the target is a body, to the points' velocity gradients G e along
// the world direction e. Appended to terms.
void appendFrictionTerms(
    const PointFriction& f, const StiffnessTerm& normal,
    const std::function<void(const Eigen::VectorXd& e, StiffnessTerm& t)>& gradients,
    std::vector<StiffnessTerm>& terms);

// Friction with a stick anchor (schemas/contact_friction.md, "Stick anchors"): a collocation
// point in contact carries an anchor z on the target (world coordinates, part of the
// integrated state); with the elastic slip r = x - z, its tangential part d = P_t r, the
// tangential stiffness k_t = c_t w_i (N/m) and the slip limit d_lim = mu f_n / k_t,
//   stick (|d| <= d_lim):  f_t = -k_t d,              dz/dt = 0,
//   slip  (|d| >  d_lim):  f_t = -mu f_n d / |d|,     dz/dt = (|d| - d_lim) / eta  d / |d|,
// so |f_t| <= mu f_n exactly, a sticking point does not move (no creep), and a slipping
// point's anchor trails it by eta |v_slip| beyond the limit: Perzyna's viscoplastic return
// to the Coulomb cone with relaxation time eta. The power taken out is
// P = -f_t . dz/dt = mu f_n (|d| - d_lim) / eta >= 0, the energy held in the tangential
// spring 1/2 k_t min(|d|, d_lim)^2.
// Linearisation (d, e1 = d / |d|, e2 = n x e1 in 3D, beta = d_lim / |d|):
//   stick: d f_t / d r = -k_t (e1 e1^T + e2 e2^T),
//   slip:  d f_t / d r = -mu f_n / |d| e2 e2^T,   d f_t / d f_n = -mu e1,
//          d zdot / d r = (e1 e1^T + (1 - beta) e2 e2^T) / eta,
//          d zdot / d f_n = -mu / (k_t eta) e1.
struct AnchoredFriction {
  Eigen::VectorXd force;  // f_t (d components, N)
  Eigen::VectorXd rate;   // dz/dt (d components, m/s)
  double power = 0.0;     // W >= 0
  double energy = 0.0;    // J, the tangential spring's
  bool sticking = true;
  // Slipping with the anchor on the slip limit, d = d_lim e1 with e1 held (the quasi-static
  // projection's iteration: f_t = -mu f_n e1 depends on the normal force only).
  bool following = false;
  Eigen::VectorXd e1, e2;  // unit tangents (e2 empty in 2D)
  double d = 0.0;          // |d| (m)
};

// branch: kDecide by |d| against d_lim; kStick holds the stick branch (the spring, whatever
// |d|); kFollow slips along the given e1 with the anchor on the slip limit (`following`).
// The quasi-static projection's Newton iteration holds each point's branch: with the law's
// switch inside it, a point whose anchor trails it by eta |v_slip| flips to stick under a
// correction of a fraction of a nanometre and back, and the iteration cycles.
enum class FrictionBranch { kDecide, kStick, kFollow };
AnchoredFriction anchoredFriction(const FrictionLaw& law, double normal_force, double k_t,
                                  const Eigen::VectorXd& r, const Eigen::VectorXd& n,
                                  FrictionBranch branch = FrictionBranch::kDecide,
                                  const Eigen::VectorXd* e1 = nullptr);

// The Newton-matrix terms of an anchored point beside its normal term `normal`: stick: two
// (3D; 2D one) tangential stiffness terms (kNormal kind, symmetric in the bodies' positions,
// with the anchor's columns -e); slip: the stiffness along e2, the anchor's relaxation along
// e1 and the normal force's share (kFrictionLoad) with the anchor's rows. anchor: the index
// of the point's first anchor entry among the pair's anchors; k_t as above; gradients as for
// appendFrictionTerms (here also t.bpC: the position gradients G_p e).
void appendAnchoredTerms(
    const FrictionLaw& law, const AnchoredFriction& f, double normal_force, double k_t, int anchor,
    const StiffnessTerm& normal,
    const std::function<void(const Eigen::VectorXd& e, StiffnessTerm& t)>& gradients,
    std::vector<StiffnessTerm>& terms);

// The friction at a point with normal force f_n >= 0 (N), relative velocity v and unit
// normal n (both d = 2 or 3 components).
PointFriction coulombFriction(const FrictionLaw& law, double normal_force, const Eigen::VectorXd& v,
                              const Eigen::VectorXd& n);

}  // namespace ffriga
