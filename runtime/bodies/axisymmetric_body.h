// Axisymmetric flexible body (2D SID data: x = radius, y = axis): the special case of Eq. (1)
// whose rigid motion is a translation along the common axis, the inertial y axis (paper
// Sect. 5). The body's own axis points along s * y_inertial, s = +1 or -1 (a body turned by
// 180 degrees about a radial axis), so a point with meridian coordinates (x_r, x_y) is at
//   world = (x_r, Y + s x_y).
// With V = dY/dt and ct = Ct(:, y) (the axial column, Ct^T = int rho Phi dV of the body of
// revolution), T = 1/2 m V^2 + s V ct . qdot + 1/2 qdot^T Me qdot, so
//   [ m      s ct^T ] [dV/dt ]   [ F_y + m g_y                      ]
//   [ s ct   Me     ] [qddot ] = [ Q + s ct g_y - Ke q - De qdot    ]
// (no quadratic velocity terms without rotation). Only g_y acts (gravity across the axis
// would break the symmetry and is rejected by the scene loader).
#pragma once

#include "runtime/bodies/body_model.h"

namespace ffriga {

class AxisymmetricBody : public BodyModel {
 public:
  AxisymmetricBody(std::string name, std::shared_ptr<const FlexibleBodySid> sid, double axis_sign);

  int numRigidPositions() const override { return 1; }
  int numRigidVelocities() const override { return 1; }
  double axisSign() const { return sign_; }

  BodyPose pose(const double* sp) const override;
  void positionRates(const double* sp, const double* sv, double* spdot) const override;
  void accelerations(const double* sp, const double* sv, const double* h_applied,
                     const Eigen::Vector3d& gravity, double* accel) const override;
  void solveMass(const double* sp, Eigen::MatrixXd& B) const override;
  void massBlocks(const double* sp, Eigen::MatrixXd& C, Eigen::MatrixXd& Mrr) const override;
  Eigen::VectorXd pointVelocity(const BodyPose& pose, const double* sv, const VectorRef& x,
                                const VectorRef& u_dot) const override;
  void pointGradients(const BodyPose& pose, const VectorRef& x, const Eigen::MatrixXd& Phi_x,
                      const VectorRef& n, Eigen::VectorXd& bv, Eigen::VectorXd& bp) const override;
  void addRigidPointForce(const BodyPose& pose, const VectorRef& x, const VectorRef& f,
                          double* h) const override;
  double kineticEnergy(const double* sp, const double* sv) const override;
  double gravityEnergy(const double* sp, const Eigen::Vector3d& gravity) const override;
  void momentum(const double* sp, const double* sv, Eigen::Vector3d& linear,
                Eigen::Vector3d& angular) const override;

 private:
  double sign_;
  Eigen::VectorXd ct_;       // axial column of Ct
  Eigen::VectorXd MeInvCt_;  // Me^-1 ct
  double schur_;             // m - ct^T Me^-1 ct
};

}  // namespace ffriga
