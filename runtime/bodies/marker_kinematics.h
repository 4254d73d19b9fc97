// Kinematics of a marker (runtime/bodies/body_marker.h) on a 3D body in the floating frame,
// inertial components, for joints, force elements and sensors. With the body state
// z = [v, w, qdot] (body components, Eq. 1) and A the body's rotation matrix:
//
//   point   R = r_R + A p,            p = x0 + Phi q,
//           dR/dt = G z,              G = A [E, -p~, Phi],
//           d2R/dt2 = G dz/dt + b,    b = A [w x v + w x (w x p) + 2 w x (Phi qdot)];
//   vector  U = A u,                  u = u0 + (Psi q) x u0,
//           dU/dt = G z,              G = A [0, -u~, -u0~ Psi],
//           d2U/dt2 = G dz/dt + b,    b = A [w x (w x u) + 2 w x ((Psi qdot) x u0)].
// Each is the exact time derivative of its position-level expression (dr_R/dt = A v), so
// constraints built from them have consistent position, velocity and acceleration levels.
#pragma once

#include <Eigen/Dense>

#include "runtime/bodies/body_marker.h"
#include "runtime/bodies/floating_body.h"

namespace ffriga {

struct MarkerKinematics {
  Eigen::Vector3d value = Eigen::Vector3d::Zero();  // R (m) or U (1)
  Eigen::Vector3d rate = Eigen::Vector3d::Zero();   // G z
  Eigen::Vector3d bias = Eigen::Vector3d::Zero();   // b
  Eigen::MatrixXd G;                                // 3 x numVelocities
};

void markerPoint(const FloatingBody3d& body, const double* sp, const double* sv,
                 const BodyMarker& m, MarkerKinematics& k);
void markerVector(const FloatingBody3d& body, const double* sp, const double* sv,
                  const BodyMarker& m, const Eigen::Vector3d& u0, MarkerKinematics& k);

// The ground: a fixed inertial point or vector (G with no columns, rate and bias zero).
void groundKinematics(const Eigen::Vector3d& value, MarkerKinematics& k);

// Generalised force G^T f of a force f (inertial, N) at the marker point, added to h
// (numVelocities entries).
void addMarkerForce(const FloatingBody3d& body, const double* sp, const BodyMarker& m,
                    const Eigen::Vector3d& f, double* h);

}  // namespace ffriga
