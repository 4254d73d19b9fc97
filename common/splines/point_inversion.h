// Point inversion on a NURBS patch of parametric dimension d = space dimension s (a solid
// or a plane section): the parameters xi of a physical point x, x(xi) = x (Eq. 4).
//
// Start: the nearest of a grid of samples (`samples` per direction, refined where the
// patch has more knot spans). Iteration: Gauss-Newton with a Levenberg-Marquardt term,
//   (J^T J + mu I) dxi = J^T (x - x(xi)),
// clamped to the parameter domain, so that points on boundary faces, on the axis of a
// half-disk or near collapsed edges (singular J) converge too. Success when
// |x(xi) - x| <= tolerance (m).
#pragma once

#include <array>

#include <Eigen/Dense>

#include "common/splines/nurbs_patch.h"

namespace ffriga {

struct InversionResult {
  bool found = false;
  std::array<double, 3> xi{0, 0, 0};
  double distance = 0.0;  // |x(xi) - x| at the end, m
};

InversionResult invertPoint(const NurbsPatch& patch, const Eigen::VectorXd& x, double tolerance,
                            int samples = 24);

}  // namespace ffriga
