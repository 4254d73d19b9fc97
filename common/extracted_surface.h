// Evaluation of a Bezier-extracted contact surface (common/sid.h, ContactSurface) with
// given, possibly deformed, control points: the runtime's view of a body's contact face.
//
// On element e with box [lo, hi] (surface parameters s, dimension dc = 1 or 2):
//   t_a = (s_a - lo_a) / (hi_a - lo_a),   Bern_b(t) = prod_a C(p_a, b_a) t^b_a (1-t)^(p_a-b_a),
//   B_k(s) = sum_b E_e(k, b) Bern_b(t),     R_k = w_k B_k / sum_l w_l B_l   (paper Eq. 4),
//   x(s) = sum_k R_k(s) P_k,
// derivatives with respect to s by the chain rule (d/ds_a = 1/(hi_a - lo_a) d/dt_a) and the
// quotient rule (rationalize(), rational_basis.h). Units: P in metres, s dimensionless.
#pragma once

#include <Eigen/Dense>

#include "common/nurbs_patch.h"
#include "common/sid.h"

namespace ffriga {

// Bernstein polynomials of degree p (<= kMaxDegree) and their first and second derivatives
// at t: ders[k * (p + 1) + b] = d^k/dt^k Bern_b(t), k <= order <= 2.
void bernsteinDerivatives(int p, double t, int order, double* ders);

class ExtractedSurface {
 public:
  // points: all body control points (ncp x s, metres); weights: ncp. Function numbers in
  // the surface index these arrays.
  ExtractedSurface(const ContactSurface& surface, Eigen::MatrixXd points, Eigen::VectorXd weights);

  const ContactSurface& surface() const { return surface_; }
  int numElements() const { return static_cast<int>(surface_.element_level.size()); }
  // Replace the control points (deformed configuration), same numbering.
  void setPoints(const Eigen::MatrixXd& points) { points_ = points; }

  // Rational basis of the element's functions at surface parameters s (inside element e)
  // with derivatives up to `order` (<= 2); rows as in rational_basis.h with d = dc.
  void basis(int e, const double* s, int order, PatchBasis& out) const;
  // x(s), dx/ds (s x dc), d2x/ds2 (s x dc(dc+1)/2).
  PatchPoint evaluate(int e, const double* s, int order = 0) const;

 private:
  ContactSurface surface_;
  Eigen::MatrixXd points_;
  Eigen::VectorXd weights_;
};

}  // namespace ffriga
