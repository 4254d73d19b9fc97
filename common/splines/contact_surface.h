// The contact surface of a body (ContactSurface, below; stored in the SID): a region of one boundary
// face of a HierarchicalSpace, Bezier-extracted, with collocation points and weights for
// the contact by collocation (paper Sect. 4, Eq. 15-18).
//
// Face (dir, side): xi_dir = front (side 0) or back (side 1) of the parameter domain.
// Surface parameters s are the remaining parametric directions in increasing order
// (3D: dir 1 -> s = (xi_0, xi_2)); knot coordinates are kept (no rescaling).
// Region: a box in s; the surface elements are the face cells of the hierarchical mesh
// that lie inside it (a cell counts if inside within 1e-12 of the region size), so a
// region should follow element lines; it must contain at least one element.
//
// Extraction: on a face element of level l the hierarchical functions restricted to the
// face are E_e = C_e|face M_e, with C_e|face the columns of the volume extraction operator
// whose level-l B-spline is 1 on the face, and M_e the Kronecker product of the 1D Bezier
// extraction matrices of the level-l B-splines on that span (computed by interpolation at
// p+1 points: exact up to round-off). Rows of functions that vanish on the face are dropped.
//
// Collocation: one point per surface function that is non-zero in the region. The point
// is the Botella point restricted to the region: the s where the function's polynomial
// (hierarchical B-spline) trace attains its maximum over the region elements. Found by
// sampling 4(p+1) points per direction on every element of its support in the region,
// then projected Newton steps on the polynomial of the best element (gradient and Hessian
// of the Bernstein form), kept only if they increase the value.
// Weight: w_k = integral over the region of R_k dA (m^2 in 3D, m along the curve in 2D:
// the runtime multiplies by 2 pi r for axisymmetric bodies), by Gauss-Legendre with p+3
// points per direction per element. The weights sum to the region's area (length).
// Gauss collocation (the alternative, CollocationRule::kGauss): the p_a + 1 Gauss-Legendre
// points per direction of every region element, each with its quadrature weight times the
// surface Jacobian (m^2 in 3D, m in 2D): the penalty traction integrated by quadrature,
// sum_g Phi(s_g)^T t(s_g) w_g ~ integral of Phi^T t dA, consistent with the surface measure
// (in axisymmetric bodies the runtime's ring factor 2 pi r_g then is exact at each point,
// where a Botella weight, the integral of R_k along the meridian times 2 pi r_k, is not:
// the point on the axis has r_k = 0 and weight 0).
// outward_sign: +1 if n = dx/ds_0 x dx/ds_1 (3D) or n = (dy/ds, -dx/ds) (2D, the tangent
// rotated clockwise) points out of the body, judged against the inward parametric
// direction at the centre of the first element.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "common/splines/hierarchical_space.h"

namespace ffriga {

// Where the collocation points are (header comment): the paper's Botella points, one per
// surface function, or Gauss-Legendre points of every element.
enum class CollocationRule { kBotella, kGauss };

// Contact surface: the boundary face (3D) or edge (2D) that holds the contact region, as
// Bezier-extracted elements so that the runtime evaluates it without knot vectors:
//   on element e with parametric box [lo, hi] (dimension dc = d - 1),
//   B_k(s) = sum_b C_e(k, b) Bern_b(t),   t = (s - lo) / (hi - lo),
// with Bern_b the tensor Bernstein polynomials of `degrees` (first direction fastest), and
// the rational basis R_k = w_k B_k / sum w_l B_l with the body's weights (Eq. 4). Function
// numbers k are body control point numbers (rows of Phi).
struct ContactSurface {
  std::string name;                         // e.g. "contact"
  int dim = 0;                              // dc = 1 (2D body) or 2 (3D body)
  std::vector<int> degrees;                 // dc polynomial degrees
  Eigen::MatrixXd element_lower;            // ne x dc, surface parameters
  Eigen::MatrixXd element_upper;            // ne x dc
  std::vector<int> element_level;           // ne, hierarchical level (0 = coarsest)
  std::vector<int> function_offsets;        // ne + 1, CSR offsets into functions / extraction
  std::vector<int> functions;               // active body control points per element
  std::vector<Eigen::MatrixXd> extraction;  // per element: n_active x prod(degrees + 1)
  double outward_sign = 1.0;                // +1 if d x/ds_0 x d x/ds_1 (2D: the tangent
                                            // rotated clockwise, (dy/ds, -dx/ds)) points out
                                            // of the body, -1 otherwise
  // Collocation (Botella) points, one per surface function in the contact region
  // (Sect. 4): surface parameters, element, and weight = integral of the function over the
  // undeformed surface (m^2 in 3D; m, per radian not included, in 2D).
  Eigen::MatrixXd collocation_points;    // nc x dc
  std::vector<int> collocation_element;  // nc
  Eigen::VectorXd collocation_weights;   // nc
  CollocationRule collocation_rule = CollocationRule::kBotella;  // how they were placed
};

// `region`: lower/upper bounds of the surface parameters (entries 0..d-2). Throws
// std::invalid_argument if dir/side are invalid or the region holds no face element.
ContactSurface extractContactSurface(const HierarchicalSpace& space, int dir, int side,
                                     const ParamBox& region, const std::string& name = "contact",
                                     CollocationRule rule = CollocationRule::kBotella);

}  // namespace ffriga
