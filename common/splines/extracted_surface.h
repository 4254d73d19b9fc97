// Evaluation of a Bezier-extracted contact surface (common/splines/contact_surface.h, ContactSurface) for given,
// possibly deformed, control points (paper Eq. 4-6, 14):
//
//   on element e with box [lo, hi]:  t = (s - lo) / (hi - lo),
//   B_k(s) = sum_b C_e(k, b) Bern_b(t),   R_k = w_k B_k / sum_l w_l B_l,
//   x(s)   = sum_k R_k(s) P_k,            P_k = P0_k + Phi_k q  (deformed control points).
//
// Bern_b are tensor Bernstein polynomials (first direction fastest); derivatives are taken
// w.r.t. the surface parameters s (chain rule 1/(hi - lo) per direction). Tables follow
// common/splines/rational_basis.h (row 0 value, rows 1..dc first derivatives, then second ones).
// Parametric dimension dc = 1 (curve of a 2D body) or 2 (face of a 3D body).
//
// Outward normal (Sect. 4, Eq. 16): dc = 2: n = sign * (x_s0 x x_s1) / |..|;
// dc = 1: n = sign * (t_y, -t_x) / |t| with t = x_s0 (the 3D rule for the curve extruded
// along +z), sign = ContactSurface::outward_sign.
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "common/splines/contact_surface.h"
#include "common/splines/nurbs_patch.h"

namespace ffriga {

// Bernstein polynomials of degree p at t in [0, 1] with derivatives up to `order` (<= 2):
// out(r, i) = d^r/dt^r Bern_{i,p}(t).
void bernsteinBasis(int p, double t, int order, Eigen::MatrixXd& out);

// Point and derivatives w.r.t. the surface parameters (x, dx columns d/ds_a, ddx columns
// as rational_basis.h rows): the same record as a patch point.
using SurfacePoint = PatchPoint;

class ExtractedSurface {
 public:
  ExtractedSurface() = default;
  // `weights`: the body's control point weights (indexed by body control point number).
  // Throws std::invalid_argument if the surface data are inconsistent.
  ExtractedSurface(const ContactSurface& surface, const Eigen::VectorXd& weights);

  int dim() const { return dim_; }
  int numElements() const { return static_cast<int>(lower_.rows()); }
  const ContactSurface& surface() const { return *surface_; }
  // Body control points of element e and their number.
  const int* functions(int e) const { return surface_->functions.data() + offsets(e); }
  int numFunctions(int e) const { return offsets(e + 1) - offsets(e); }
  // All body control points used by the surface (sorted, unique).
  const std::vector<int>& allFunctions() const { return all_functions_; }
  Eigen::VectorXd elementLower(int e) const { return lower_.row(e).transpose(); }
  Eigen::VectorXd elementUpper(int e) const { return upper_.row(e).transpose(); }
  // Bounding box of the whole parameter domain.
  const Eigen::VectorXd& domainLower() const { return domain_lo_; }
  const Eigen::VectorXd& domainUpper() const { return domain_hi_; }

  // Element containing s (closed boxes, the first match), or -1 if none does.
  int findElement(const double* s) const;
  // Rational basis table of element e at s: numDerivativeRows(dim, order) x numFunctions(e).
  void basis(int e, const double* s, int order, Eigen::MatrixXd& R) const;
  // Point and derivatives; `points` holds the (deformed) control points, one row per body
  // control point (only the rows of this surface's functions are read). Members of `out`
  // above `order` keep what they held (storage is reused: no allocation in the hot path).
  void evaluate(int e, const double* s, const Eigen::MatrixXd& points, int order,
                SurfacePoint& out) const;
  // Unit outward normal from first derivatives (header comment); the second form into n,
  // whose storage is reused (the contact search calls it for every point).
  Eigen::VectorXd normal(const Eigen::MatrixXd& dx) const;
  void normal(const Eigen::MatrixXd& dx, Eigen::VectorXd& n) const;

 private:
  int offsets(int e) const { return surface_->function_offsets[e]; }

  const ContactSurface* surface_ = nullptr;
  int dim_ = 0;
  Eigen::MatrixXd lower_, upper_;
  Eigen::VectorXd domain_lo_, domain_hi_;
  std::vector<Eigen::VectorXd> element_weights_;  // weights of each element's functions
  std::vector<int> all_functions_;
};

}  // namespace ffriga
