// Static preload (paper Sect. 7): before t = 0, the elastic coordinates q of every flexible
// body are set so that their accelerations vanish,
//   F(q) = qddot(y(q)) = 0,
// with the rigid state given by the scene (positions moved only as far as the joints need
// to stay closed at the deformed markers; velocities as given), so that the run starts in
// equilibrium with gravity, the joints' reactions and the inertial loads of the rigid motion
// at t = 0 instead of ringing.
//
// Newton's method on F with the Jacobian dF/dq by difference quotients (one right-hand side
// per elastic coordinate, once; it is reused while the residual falls by 10x per step) and
// y(q) = the state with elastic coordinates q whose rigid positions are projected back onto
// the joints (Gauss-Newton in the rigid mass metric, elastic coordinates held).
// Converged when |F|_inf <= 1e-10 |Ke q|_inf (elastic accelerations zero to round-off of the
// elastic forces), at most 30 steps; otherwise ComputeError.
#pragma once

#include <Eigen/Dense>

#include "runtime/system/multibody_system.h"

namespace ffriga {

struct PreloadReport {
  int iterations = 0;
  double residual = 0.0;       // |qddot|_inf at the end
  double elastic_force = 0.0;  // |Ke q|_inf at the end (the residual's scale)
};

PreloadReport staticPreload(MultibodySystem& system, Eigen::VectorXd& y);

}  // namespace ffriga
