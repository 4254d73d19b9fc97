// The SID invariants of a reduced flexible body (common/sid/sid.h; Wallrapp / Schwertassek,
// "Dynamik flexibler Mehrkoerpersysteme", Sect. 6.4; paper Sect. 2, Eq. 1), computed exactly
// from the IGA model:
//
//   * rigid-body invariants m, m c = int rho x0 dV, J0 = int rho (x0.x0 E - x0 x0^T) dV by
//     Gauss quadrature of the geometry map with more points than p + 1 (the integrands are
//     rational). Measured relative errors of m and J0 of the sphere (degree 3, n x n x 2n
//     elements) with p + 1 + k points: n = 2: 4e-6 (k = 0), 2e-9 (k = 2), 1e-10 (k = 3);
//     n = 4: 3e-9 (k = 0), 7e-15 (k = 2); n = 8: 2e-11 (k = 0), 1e-15 (k = 1). igaprep uses
//     k = 2 (the paper's models have n >= 8).
//   * elastic invariants from the scalar mass matrix Ms (elasticity_assembly.h): since
//     x0 = sum_b R_b X_b and Phi(x0) = sum_b R_b Phi_b, every integral of a product of two
//     such fields is a bilinear form in Ms:
//       Ct^T   = int rho Phi dV                        = sum_ab Ms_ab Phi_b
//       G_i    = int rho x0 Phi_i^T dV                 = X^T Ms Phi_i            (3 x 3)
//       Cr0^T  = int rho x0~ Phi dV:  column i         = axial(G_i^T - G_i)
//       Cr1_j(:, i) = int rho Phi_j~ Phi_i dV          = sum_ab Ms_ab Phi_aj x Phi_bi
//       J1_j   = -int rho (x0~ Phi_j~ + Phi_j~ x0~) dV = 2 tr(G_j) E - G_j - G_j^T
//       Oe(i, :) = [G00 - tr, G11 - tr, G22 - tr, G01 + G10, G12 + G21, G02 + G20](G_i)
//     (a~ b~ = b a^T - (a.b) E; w~ w~ x = w (w.x) - |w|^2 x).
//   Kept: zeroth and first order terms in q, which carry the inertia coupling, the
//   gyroscopic (Coriolis) and centrifugal terms of Eq. (1). Dropped: second-order terms
//   (int rho Phi_i^T Phi_j dV enters only through Me = E, the q^2 part of J), small
//   deformations as in the paper. Geometric stiffening is not modelled.
//   * axisymmetric bodies: the section (r, y) revolved about y; for a material point at angle
//     t, x0 = (r cos t, y, r sin t) and u = (u_r cos t, u_y, u_r sin t). Integrating over t:
//     Ct has a y component only, Cr0 = Cr1 = 0, and G_i = diag(a/2, b, a/2) with
//     a = int rho r u_r dV, b = int rho y u_y dV (dV of the full body of revolution).
//
// Units: kg, kg m, kg m^2; per unit q (kg^(1/2) m): Ct kg^(1/2), Cr0 and J1 kg^(1/2) m,
// Cr1 dimensionless (kg m^2 / (kg^(1/2) m)^2), Oe kg^(1/2) m.
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "common/sid/sid.h"
#include "common/splines/spline_space.h"
#include "preproc/assembly/elasticity_assembly.h"

namespace ffriga {

struct MassProperties {
  double mass = 0.0;                                       // kg
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();  // kg m, about the geometry origin
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();       // kg m^2, about the geometry origin
  Eigen::Vector3d centreOfMass() const { return first_moment / mass; }
  // The same body seen from a frame with origin o (same axes).
  MassProperties shifted(const Eigen::Vector3d& o) const;
};

// gauss_points[a]: points per direction (p + 1 + extra is the caller's choice).
MassProperties massProperties(const SplineSpace& space, double density, bool axisymmetric,
                              const std::array<int, 3>& gauss_points);

// Fills sid->Ct, Cr0, Cr1, J1, Oe from Ms, the control points X (ncp x s, body frame) and
// the modes Phi at every control point ((ncp * s) x nq).
void computeElasticInvariants(const SparseMatrix& Ms, const Eigen::MatrixXd& X,
                              const Eigen::MatrixXd& Phi, bool axisymmetric, FlexibleBodySid* sid);

}  // namespace ffriga
