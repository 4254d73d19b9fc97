// Rigid-body displacement fields in DOF space: u(x) = t + w x x (3D: three translations
// and three rotations about the origin of the geometry) or, for an axisymmetric model,
// the one rigid motion that keeps the body axisymmetric: translation along the axis y.
// Because x = sum_k R_k X_k, the field is exact with control-point values u_k = t + w x X_k.
// Columns: 3D (t_x, t_y, t_z, w_x, w_y, w_z); axisymmetric (t_y). Units: m per unit t, m
// per radian for w.
#pragma once

#include <Eigen/Dense>

#include "common/splines/spline_space.h"
#include "preproc/assembly/dof_map.h"

namespace ffriga {

Eigen::MatrixXd rigidBodyModes(const SplineSpace& space, const DofMap& dofs, bool axisymmetric);

}  // namespace ffriga
