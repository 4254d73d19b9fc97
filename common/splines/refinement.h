// Refinement of B-spline spaces and NURBS patches.
//
// Transfer matrix. If the space S(U, p) is contained in S(Ubar, pbar) (knot insertion,
// degree elevation or both), every coarse basis function is a combination of fine ones:
//
//   N_i(u) = sum_j T(j, i) Nbar_j(u),   and a spline keeps its shape when  Pbar = T P.
//
// For knot insertion T is built by Boehm's single-knot insertion (Piegl & Tiller A5.1,
// applied to all coefficients at once: the result equals A5.4 RefineKnotVectCurve and the
// Oslo algorithm), for general non-uniform knots; paper Eq. (8) and (11) are its special
// case of uniform knots halved. For degree elevation T is obtained by collocation at the
// Greville abscissae of the elevated space (Schoenberg-Whitney guarantees a regular
// system); it gives the same coefficients as Piegl & Tiller A5.9.
// Rational patches are refined in homogeneous coordinates [w P, w] (Piegl & Tiller 5.2).
#pragma once

#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "common/splines/knot_vector.h"
#include "common/splines/nurbs_patch.h"

namespace ffriga {

// Inserts the knots `X` (any order, repetitions allowed, inside [U.front(), U.back()]) into
// U. Returns T (nbar x n) and stores the refined knot vector in *refined.
// Throws std::invalid_argument if a knot is outside the domain or would exceed multiplicity p.
Eigen::MatrixXd knotInsertionMatrix(const KnotVector& U, const std::vector<double>& X,
                                    KnotVector* refined);

// Degree elevation by t >= 0: every distinct knot gains multiplicity t. Returns T.
Eigen::MatrixXd degreeElevationMatrix(const KnotVector& U, int t, KnotVector* elevated);

// Transfer matrix between any two nested spaces S(coarse) in S(fine) with the same degree
// (fine contains every knot of coarse with at least its multiplicity). Throws otherwise.
Eigen::SparseMatrix<double> refinementMatrix(const KnotVector& coarse, const KnotVector& fine);

// Knots that subdivide every non-empty span of U into (perSpan + 1) equal parts.
std::vector<double> uniformInsertionKnots(const KnotVector& U, int perSpan);

// Applies a 1D transfer matrix T (nbar x n) along parametric direction `dir` of a patch.
NurbsPatch applyAlongDirection(const NurbsPatch& patch, int dir, const Eigen::MatrixXd& T,
                               const KnotVector& newKnots);

NurbsPatch insertKnots(const NurbsPatch& patch, int dir, const std::vector<double>& X);
NurbsPatch elevateDegree(const NurbsPatch& patch, int dir, int t);

}  // namespace ffriga
