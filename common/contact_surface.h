// The contact surface of a body (common/sid.h, ContactSurface): a region of one boundary
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
// outward_sign: +1 if n = dx/ds_0 x dx/ds_1 (3D) or n = (dy/ds, -dx/ds) (2D, the tangent
// rotated clockwise) points out of the body, judged against the inward parametric
// direction at the centre of the first element.
#pragma once

#include <string>

#include "common/hierarchical_space.h"
#include "common/sid.h"

namespace ffriga {

// `region`: lower/upper bounds of the surface parameters (entries 0..d-2). Throws
// std::invalid_argument if dir/side are invalid or the region holds no face element.
ContactSurface extractContactSurface(const HierarchicalSpace& space, int dir, int side,
                                     const ParamBox& region, const std::string& name = "contact");

}  // namespace ffriga
