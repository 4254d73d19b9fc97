// Closest point on a contact surface (paper Sect. 4, Eq. 15): find surface parameters s with
//
//   (d x_T / d s)^T (x_C - x_T(s)) = 0,
//
// by Newton's method on phi(s) = 1/2 |x_T(s) - x_C|^2: gradient g_a = x_a . r,
// Hessian H_ab = x_a . x_b + r . x_ab (r = x_T - x_C); Gauss-Newton (H = x_a . x_b) where H
// is not positive definite. Steps are clamped to the parameter domain and may cross element
// boundaries (the element is looked up again). Robust fallback: when Newton fails to
// converge, or no start is given, every element is sampled on a grid and Newton restarts
// from the nearest sample; if it fails again the nearest sample is returned (converged =
// false). Newton is restarted from the best samples of the `restarts` nearest elements and
// the closest converged result is kept.
#pragma once

#include <Eigen/Dense>

#include "common/splines/extracted_surface.h"
#include "runtime/bodies/space_vector.h"

namespace ffriga {

struct SurfaceProjection {
  int element = -1;
  Eigen::VectorXd s;   // surface parameters
  SurfacePoint point;  // x_T(s) with first derivatives
  bool converged = false;
  // True if the closest point is a proper foot point (Eq. 15 holds: x_C - x_T is normal to
  // the surface), false if it lies on the domain boundary with x_C beyond the surface's edge.
  bool orthogonal = false;
};

struct ProjectionOptions {
  int max_iterations = 30;
  int samples_per_element = 4;  // per direction, for the fallback search
  int restarts = 4;             // Newton starts from the nearest samples of this many elements
  // Convergence: |dx_a . r| <= tol * |dx_a| * (|r| + length scale) for every a.
  double tolerance = 1e-12;
  // Orthogonality test at the domain boundary (relative, dimensionless).
  double edge_tolerance = 1e-6;
};

// `points`: world (deformed) control points, one row per body control point. `start`: a
// previous solution to warm-start from (element >= 0 and s set), or nullptr.
SurfaceProjection closestPoint(const ExtractedSurface& surface, const Eigen::MatrixXd& points,
                               const VectorRef& x, const SurfaceProjection* start,
                               const ProjectionOptions& options = ProjectionOptions());
// The same into `p`, whose storage is reused (the contact search's per-thread workspace:
// no allocation once sized); `start` must not be `p`.
void closestPoint(const ExtractedSurface& surface, const Eigen::MatrixXd& points,
                  const VectorRef& x, const SurfaceProjection* start, SurfaceProjection& p,
                  const ProjectionOptions& options = ProjectionOptions());

}  // namespace ffriga
