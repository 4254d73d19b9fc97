// Displacement and stress modes at points of a body (common/sid/sid.h, SampledModes):
//
//   u(x)     = sum_k R_k(x) Phi_k q                     (Eq. 14, m)
//   sigma(x) = D B(x) Phi_loc q = S(x) q                (Pa; preproc/assembly/strain_operator.h)
//
// for the reduced model's modes Phi (control points, (ncp s) x nq). sigma(t) = S q(t) is
// then exact for the reduced model. Points are given by their element and parameters in
// a SplineSpace. Where the geometry map is singular at a point (|det J| below 1e-6 of its
// value at the element's centre: the collapsed edge of the half-disk, the axis and equator
// of the solid sphere) the discrete strain is unbounded (seen: 1e26 Pa per unit q at the
// collapsed point of the half-disk with derivatives taken 1e-3 of the span inside), so the
// stress there is the one at 5 % of the element's span inside it: a picture, not a value
// to trust. The displacement is always the one at the point.
// Axisymmetric points on the axis (r <= 1e-12 of the body's size) use the hoop strain's
// limit d u_r / d r. Points are independent: computed in parallel, same bits on any
// number of threads.
#pragma once

#include <array>
#include <vector>

#include "common/sid/sid.h"
#include "common/splines/spline_space.h"
#include "preproc/assembly/strain_operator.h"

namespace ffriga {

struct ParametricPoint {
  int element = -1;
  std::array<double, 3> xi{0, 0, 0};
};

// origin: the body frame's origin in the space's coordinates (points are stored relative to
// it); size: the body's size (m), for the on-axis test.
SampledModes sampleModes(const SplineSpace& space, const std::vector<ParametricPoint>& points,
                         const Eigen::MatrixXd& Phi, const IsotropicMaterial& material,
                         bool axisymmetric, const Eigen::VectorXd& origin, double size);

}  // namespace ffriga
