// Linear isotropic elasticity on a SplineSpace (paper Eq. 12: Me qdd + Ke q = f, here the
// full, unreduced matrices), for u(x) = sum_k R_k(x) u_k (isoparametric, Eq. 4-5).
//
//   K = int B^T D B dV   (N/m),   M = int rho R^T R dV   (kg, consistent mass),
//   Ms(a, b) = int rho R_a R_b dV  (kg, the scalar mass matrix),
//
// with Lame constants lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)).
// with D and B from preproc/assembly/strain_operator.h (the same pieces recover stresses,
// preproc/assembly/stress_modes.h); per element K_e = sum_g B_g^T D B_g w_g detJ_g in the factored
// form isotropicStiffness (products of the Gauss point gradient tables).
//   * solid (3D): strains (e_xx, e_yy, e_zz, g_xy, g_yz, g_xz), dV = dx dy dz.
//   * axisymmetric: the meridian section (x = r >= 0, y = axis), u = (u_r, u_y); strains
//     (e_rr, e_yy, e_tt = u_r / r, g_ry), dV = 2 pi r dr dy, so that K and M are those of the
//     full body of revolution (torsion-free axisymmetric deformation).
// Gauss-Legendre quadrature with gauss_points[a] points per direction on every element
// (p + 1 is the usual choice; Gauss points are interior, so collapsed edges and the axis
// r = 0 are never evaluated). Since x = sum_b R_b X_b, Ms gives every mass moment of the
// undeformed body exactly: int rho x x^T dV = X^T Ms X (used by sid_invariants).
//
// Storage: K and M are numDofs x numDofs, upper triangle only (CHOLMOD stype = 1), in the
// DOF numbering of the DofMap (tied control points and the axis condition applied). Ms is
// ncp x ncp, upper triangle, with coincident control points lumped onto their node (the
// smallest index of the group): rows and columns of the other points are empty; a sum
// sum_ab Ms(a, b) f_a g_b is exact for control-point data f, g that agree on tied points.
// Assembly runs over elements in parallel (OpenMP) and adds into a precomputed pattern,
// every entry in element order: the matrices are the same bits for any thread count.
#pragma once

#include <array>

#include "common/mechanics/isotropic_material.h"
#include "common/splines/spline_space.h"
#include "preproc/assembly/dof_map.h"
#include "preproc/solvers/sparse_matrix.h"

namespace ffriga {

struct ElasticityModel {
  bool axisymmetric = false;
  IsotropicMaterial material;
  std::array<int, 3> gauss_points{4, 4, 4};  // per parametric direction, >= 1
};

struct ElasticSystem {
  SparseMatrix K;   // N/m, upper triangle
  SparseMatrix M;   // kg, upper triangle
  SparseMatrix Ms;  // kg, upper triangle, ncp x ncp
};

// Throws ComputeError if the geometry map is singular at a Gauss point.
ElasticSystem assembleElasticity(const SplineSpace& space, const DofMap& dofs,
                                 const ElasticityModel& model);

}  // namespace ffriga
