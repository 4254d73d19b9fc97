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

#include "common/sid.h"
#include "common/spline_space.h"
#include "preproc/dof_map.h"

namespace ffriga {

// Throws InputError (naming the marker) if xi lies outside the parameter domain.
Marker evaluateMarker(const SplineSpace& space, const std::string& name,
                      const std::vector<double>& xi);

// Rows of C (nr x numDofs) with C u = 0 the tangent frame conditions at xi.
Eigen::MatrixXd tangentFrameConditions(const SplineSpace& space, const DofMap& dofs,
                                       const std::vector<double>& xi, bool axisymmetric);

}  // namespace ffriga
