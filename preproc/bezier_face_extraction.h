// The contact surface of a tensor-product patch as Bezier-extracted elements (common/sid.h
// ContactSurface), so that the runtime evaluates it without knot vectors.
//
// Per surface direction b with knot vector U_b of degree p_b, inserting every interior
// break until it has multiplicity p_b gives the transfer matrix T_b (knotInsertionMatrix,
// Piegl & Tiller A5.4): N_k = sum_j T_b(j, k) Nbar_j. On element e (span number j_b) the
// fine functions j_b p_b .. j_b p_b + p_b are the Bernstein polynomials of that span, so
//   C_e(k, t) = prod_b T_b(j_b p_b + t_b, k_b)     (Borden et al., IJNME 87, 2011, Sect. 3)
// with t = (t_0, t_1) numbered first direction fastest. On the face xi_a = const only the
// functions with the first (xi_a_min) or last (xi_a_max) index along a are non-zero, and
// equal to the surface functions there.
//
// Elements: the face elements whose box overlaps the contact region with positive area.
// Collocation points and weights stay empty here: they are the Botella points of the
// hierarchical contact surface (issue 3, common/contact_surface.*).
#pragma once

#include <string>

#include "common/sid.h"
#include "common/spline_space.h"
#include "preproc/contact_region.h"

namespace ffriga {

ContactSurface extractFaceSurface(const TensorSpace& space, const ContactRegion& region,
                                  const std::string& name);

}  // namespace ffriga
