// Rigid bodies as FloatingBody3d with no elastic coordinates (nq = 0): Eq. (1) reduces to the
// Newton-Euler equations in body components,
//   [ m E    m c~^T ] [dv/dt]   [ f - w x (m v + w x m c)                     ]
//   [ m c~   J0     ] [dw/dt] = [ n - w x (m c x v + J0 w) - v x (m v + w x m c) ],
// so one body model serves flexible, rigid and frozen bodies alike.
//
// A scene-defined rigid body gives its mass m (kg), centre of mass c (body frame, m) and its
// inertia tensor I_c about the centre of mass in body axes (kg m^2). The SID invariants are
//   m c = m * c,   J0 = I_c + m (c.c E - c c^T)       (parallel axis theorem),
// and I_c must be symmetric positive definite and satisfy the triangle inequalities of the
// principal moments (I1 + I2 >= I3 and cyclic: a physical mass distribution).
// A frozen body keeps the SID's rigid invariants, contact surfaces and markers and drops
// its elastic coordinates (a flexible body used as a rigid one).
#pragma once

#include <string>

#include <Eigen/Dense>

#include "common/sid/sid.h"

namespace ffriga {

struct RigidBodyProperties {
  double mass = 0.0;                                         // kg
  Eigen::Vector3d centre_of_mass = Eigen::Vector3d::Zero();  // body frame, m
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();         // about the centre, kg m^2
};

// Throws InputError (a sentence naming the rule broken, for the caller to prefix with the
// file, line and key) for a non-positive mass or an inertia tensor that is not symmetric,
// not positive definite or violates the triangle inequalities.
FlexibleBodySid rigidBodySid(const std::string& name, const RigidBodyProperties& p);

// The SID's rigid part only: nq = 0, the same mass, first moment, inertia, control points,
// contact surfaces and marker positions.
FlexibleBodySid frozenSid(const FlexibleBodySid& sid);

}  // namespace ffriga
