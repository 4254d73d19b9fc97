// The initial state of a scene's system and the integrator's absolute tolerances, from the
// bodies' initial poses (runtime/scene/scene_bodies.h), and the check that no two bodies
// start inside each other.
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "common/input/yaml_input.h"
#include "runtime/scene/scene_bodies.h"
#include "runtime/system/multibody_system.h"

namespace ffriga {

// The scene's absolute tolerances per kind of state entry (integrator.atol_*).
struct AbsoluteTolerances {
  double position = 1e-12;          // m
  double velocity = 1e-8;           // m/s
  double rotation = 1e-10;          // quaternion entries (1)
  double angular_velocity = 1e-6;   // rad/s
};

// y0 in the system's layout (velocities in body components, Eq. 1) and atol per entry;
// `axisymmetric`: the scene's bodies are axisymmetric (state: Y and V_y); rtol: the
// integrator's relative tolerance (the stick anchors' atol).
void assembleInitialState(const MultibodySystem& sys, const std::vector<InitialPose>& poses,
                          bool axisymmetric, const AbsoluteTolerances& tol, double rtol,
                          Eigen::VectorXd& y0, Eigen::VectorXd& atol);

// Bodies must not start inside each other: a penetration beyond the pair's tolerance
// (ContactPair::penetrationTolerance) is bad input (contacts[c]), with the depth in the
// message.
void checkInitialPenetration(const YamlDocument& doc, const MultibodySystem& sys,
                             const Eigen::VectorXd& y0);

}  // namespace ffriga
