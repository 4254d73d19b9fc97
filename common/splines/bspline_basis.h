// Univariate B-spline basis functions and their derivatives by the non-recursive
// algorithms of Piegl & Tiller (A2.2 BasisFuns, A2.3 DersBasisFuns), Cox-de Boor
// recursion (paper Eq. 2-3) evaluated as a triangular table.
//
// On span i (u_i <= u < u_{i+1}) the p+1 functions N_{i-p,p}, ..., N_{i,p} are non-zero;
// results are stored in that order.
#pragma once

#include "common/splines/knot_vector.h"

namespace ffriga {

// A2.2: N[j] = N_{span-p+j,p}(u), j = 0..p.
void basisFunctions(const KnotVector& U, int span, double u, double* N);

// A2.3: ders[k * (p + 1) + j] = d^k/du^k N_{span-p+j,p}(u), k = 0..nders, j = 0..p.
// Derivatives of order k > p are zero. nders <= kMaxDegree.
void basisFunctionDerivatives(const KnotVector& U, int span, double u, int nders, double* ders);

}  // namespace ffriga
