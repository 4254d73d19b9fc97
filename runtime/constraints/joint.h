// Joints between two markers, or between the ground and a marker (DESIGN.md "Multibody"):
// holonomic, scleronomic constraints g(positions) = 0 whose forces enter Eq. (1) of each
// body as J_b^T lambda (runtime/system/multibody_system.h has the solve).
//
// Every joint has a frame: axes e1, e2, e3 (e3 the revolute or sliding axis), given in
// inertial components at t = 0 and attached to the material at each end's marker
// (body-frame components a_i at end a, b_i at end b; on the ground fixed). With R_a, R_b the
// end points and U(.) the current inertial direction of an attached vector
// (runtime/bodies/marker_kinematics.h), d = R_b - R_a:
//
//   spherical  d = 0                                                   3 equations
//   revolute   d = 0,  U(a1).U(b3) = 0,  U(a2).U(b3) = 0               5
//   fixed      d = 0,  U(a2).U(b3) = 0,  U(a3).U(b1) = 0,  U(a1).U(b2) = 0    6
//   prismatic  U(a1).d = 0,  U(a2).d = 0,  and the three of fixed       5
//
// The rotational equations of fixed and prismatic are the three independent components of
// the relative rotation for frames that stay close to aligned, as they do. For each
// equation the rows of J (dg/dt = J_a z_a + J_b z_b) and the bias (d2g/dt2 = J dz/dt + bias)
// follow from the marker kinematics by the product rule:
//   g = X.Y:  J = X^T G_Y + Y^T G_X,  bias = b_X.Y + 2 dX/dt.dY/dt + X.b_Y.
#pragma once

#include <string>
#include <string_view>

#include <Eigen/Dense>

#include "runtime/bodies/body_marker.h"
#include "runtime/bodies/floating_body.h"

namespace ffriga {

enum class JointType { kSpherical, kRevolute, kFixed, kPrismatic };

using JointEnd = MarkerEnd;  // runtime/bodies/body_marker.h

// The joint's equations at one state.
struct JointRows {
  Eigen::VectorXd g;     // values (m for points and d, 1 for directions)
  Eigen::VectorXd bias;  // velocity-quadratic part of d2g/dt2
  Eigen::MatrixXd Ja;    // rows over end a's velocities (no columns for the ground)
  Eigen::MatrixXd Jb;    // rows over end b's velocities
};

// Load the joint exerts on the body of end b at its marker point, inertial components.
struct JointReaction {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // N
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();  // N m, about the marker point R_b
  double violation = 0.0;  // largest |g| of the joint's position equations (m or 1)
  // m: the largest displacement of the joint's two marker points by their bodies'
  // quasi-static coordinates, which the joint does not hold (MarkerEnd::quasi_static_Phi)
  double quasi_static_offset = 0.0;
};

class Joint {
 public:
  // End b must be a body; end a may be the ground.
  Joint(std::string name, JointType type, JointEnd a, JointEnd b);

  const std::string& name() const { return name_; }
  JointType type() const { return type_; }
  const JointEnd& end(int i) const { return i == 0 ? a_ : b_; }
  JointEnd& end(int i) { return i == 0 ? a_ : b_; }
  int numEquations() const;
  // Sets the joint axes from its inertial axes E (columns e1 e2 e3, orthonormal) and the
  // rotation matrices of the two bodies at that moment (the ground's is ignored).
  void setAxes(const Eigen::Matrix3d& E, const Eigen::Matrix3d& Aa, const Eigen::Matrix3d& Ab);

  // The equations at the ends' states (sp, sv of each body; nullptr for the ground).
  void evaluate(const double* spA, const double* svA, const double* spB, const double* svB,
                JointRows& rows) const;
  // The load on body b for the multipliers lambda of this joint's equations (generalised
  // force Jb^T lambda, its rigid part reduced to the marker point), with the violation of
  // the equations in `rows`.
  JointReaction reaction(const double* spB, const JointRows& rows,
                         const Eigen::VectorXd& lambda) const;

 private:
  std::string name_;
  JointType type_;
  JointEnd a_, b_;
};

const char* jointTypeName(JointType t);
bool parseKind(std::string_view text, JointType* type);  // the scene's word for a type

}  // namespace ffriga
