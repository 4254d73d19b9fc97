#include "preproc/assembly/rigid_body_modes.h"

namespace ffriga {

Eigen::MatrixXd rigidBodyModes(const SplineSpace& space, const DofMap& dofs, bool axisymmetric) {
  const Eigen::MatrixXd& P = space.controlPoints();
  const int ncp = static_cast<int>(P.rows());
  const int s = dofs.components();
  const int nr = axisymmetric ? 1 : 6;
  Eigen::MatrixXd U = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(ncp) * s, nr);
  for (int k = 0; k < ncp; ++k) {
    if (axisymmetric) {
      U(k * s + 1, 0) = 1.0;
      continue;
    }
    const Eigen::Vector3d x = P.row(k).transpose();
    for (int c = 0; c < 3; ++c) {
      U(k * 3 + c, c) = 1.0;
      const Eigen::Vector3d w = Eigen::Vector3d::Unit(c);
      const Eigen::Vector3d v = w.cross(x);
      for (int i = 0; i < 3; ++i) U(k * 3 + i, 3 + c) = v(i);
    }
  }
  return dofs.restrict(U);
}

}  // namespace ffriga
