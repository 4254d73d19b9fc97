// Linear isotropic elasticity at one material point: the constitutive matrix D and the
// strain operator B of a spline displacement field u(x) = sum_j R_j(x) u_j, so that
//
//   strain eps = B [u_0; u_1; ...],   stress sigma = D eps,   K = int B^T D B dV   (Eq. 12).
//
// Assembly (elasticity_assembly) and stress recovery (stress_modes) share these two pieces,
// so that the recovered stress is the one the stiffness matrix was built from.
//
// Strain components (Voigt, engineering shear strains gamma = 2 eps_ij):
//   * solid (3D):    (e_xx, e_yy, e_zz, g_xy, g_yz, g_xz)
//   * axisymmetric:  (e_rr, e_yy, e_tt, g_ry) with the hoop strain e_tt = u_r / r; on the
//     axis (r = 0, where u_r = 0) its limit d u_r / d r.
// Columns of B: function j, component c -> j * s + c (s = 3 solid, 2 axisymmetric).
// Lame constants: lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)). Units: D in
// Pa, B in 1/m (per metre of control point displacement).
#pragma once

#include <Eigen/Dense>

#include "common/mechanics/isotropic_material.h"

namespace ffriga {

// Strain components: 6 (solid) or 4 (axisymmetric).
inline int strainComponents(bool axisymmetric) { return axisymmetric ? 4 : 6; }

// D (strainComponents x strainComponents, Pa) in the component order above.
Eigen::MatrixXd constitutiveMatrix(const IsotropicMaterial& m, bool axisymmetric);

// B at one point from the physical gradients grad (s x nb: grad(c, j) = dR_j / dx_c, 1/m),
// the values R_j (nb) and, for axisymmetric bodies, the radius r (m) of the point; on_axis
// selects the hoop strain's limit on the axis. B is resized to strainComponents x s * nb.
void strainOperator(const Eigen::MatrixXd& grad, const Eigen::Ref<const Eigen::RowVectorXd>& values,
                    bool axisymmetric, double radius, bool on_axis, Eigen::MatrixXd& B);

// The element stiffness K_e = sum_g B_g^T D B_g of Gauss point tables, in factored form:
// G[c] (Gauss points x nb) holds the scaled gradients (w_g detJ_g [2 pi r_g])^(1/2) dR_j/dx_c
// (c < s) and, for axisymmetric bodies, G[2] the scaled hoop rows (...)^(1/2) R_j / r_g.
// Evaluated from the products G_i^T G_j (solid: K_ab(i, j) = lambda H_ij + mu H_ji
// + mu delta_ij tr H), the same matrix strainOperator and constitutiveMatrix give
// (tests/preproc/assembly/stress_recovery_test.cc) in a ninth of the flops. Ke: s nb x s nb, order j s + c.
void isotropicStiffness(const Eigen::MatrixXd G[3], const IsotropicMaterial& m, bool axisymmetric,
                        Eigen::MatrixXd& Ke);

}  // namespace ffriga
