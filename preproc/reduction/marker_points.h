// Marker points: named material points given by their parameters xi, whose displacement is
// u(xi) = sum_k R_k(xi) u_k (sid.h Marker), and the tangent-frame conditions at a marker:
// the displacement and (3D) the infinitesimal rotation of the material there vanish,
//   u(xi) = 0,   w(xi) = 1/2 curl u(xi) = 0,
// with curl u from the physical gradients grad R_k = J^{-T} dR_k/dxi. For an axisymmetric
// model the only rigid motion is the translation along the axis: the condition is u_y = 0.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "common/sid/sid.h"
#include "common/splines/spline_space.h"
#include "preproc/assembly/dof_map.h"

namespace ffriga {

// Throws InputError (naming the marker) if xi lies outside the parameter domain.
Marker evaluateMarker(const SplineSpace& space, const std::string& name,
                      const std::vector<double>& xi);

// A face marker (3D): the rigid motion that fits a whole boundary face best, as a joint
// attached to the face sees it (the averaging "RBE3" attachment of FE codes). With the face
// centroid xc, r = x - xc, area A and the face's area tensor I_A = int (r.r E - r r^T) dA:
//   position  xc,
//   translation  u_M = 1/A int u dA                 -> values_k = 1/A int R_k dA,
//   rotation     theta_M = I_A^-1 int r x u dA      (least squares: min int |u - u_M - theta x
//   r|^2)
//                                                  -> Psi = sum_k I_A^-1 (int R_k r~ dA) Phi_k.
// Both are exact for rigid motions of the face. Gauss quadrature with `gauss_points` per
// direction on the face elements (the caller: degree + 2). `Phi` (control point modes, 3 rows per
// control point) may have no columns (then Psi has none). `direction`, `upper`: the face
// (contact_region.h).
Marker evaluateFaceMarker(const SplineSpace& space, const std::string& name, int direction,
                          bool upper, int gauss_points, const Eigen::MatrixXd& Phi);

// Rotation modes of a 3D marker (sid.h Marker::Psi): the small rotation of the material at
// xi per unit q, w = 1/2 curl u = 1/2 sum_k grad R_k x u_k, so
//   Psi = 1/2 sum_k skew(grad R_k) Phi_k       (3 x nq),
// with Phi_k the rows of the control point modes (space_dim rows per control point) and
// grad R_k = J^{-T} dR_k/dxi. Throws InputError if the geometry map is singular at xi.
Eigen::MatrixXd markerRotationModes(const SplineSpace& space, const std::string& name,
                                    const std::vector<double>& xi, const Eigen::MatrixXd& Phi);

// Rows of C (nr x numDofs) with C u = 0 the tangent frame conditions at xi.
Eigen::MatrixXd tangentFrameConditions(const SplineSpace& space, const DofMap& dofs,
                                       const std::vector<double>& xi, bool axisymmetric);

}  // namespace ffriga
