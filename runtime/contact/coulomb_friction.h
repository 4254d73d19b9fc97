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
  double slip_velocity = 0.0;  // eps, m/s (> 0 when mu > 0)
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

// The friction at a point with normal force f_n >= 0 (N), relative velocity v and unit
// normal n (both d = 2 or 3 components).
PointFriction coulombFriction(const FrictionLaw& law, double normal_force, const Eigen::VectorXd& v,
                              const Eigen::VectorXd& n);

}  // namespace ffriga
