// The multibody part of a scene (schemas/scene.schema.json: bodies' markers, joints,
// force elements, sensors) for runtime/scene/scene.cc: each function reads one section of
// the validated document into the system and reports errors with the file, line and key.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "common/input/yaml_input.h"
#include "runtime/system/multibody_system.h"
#include "runtime/scene/scene_bodies.h"

namespace ffriga {

// Markers of every body: the SID's (with their modes) and, for rigid and frozen bodies,
// the scene's fixed points.
using BodyMarkers = std::vector<std::map<std::string, BodyMarker>>;
BodyMarkers collectMarkers(const YamlDocument& doc, const MultibodySystem& sys);

// Joints (frames from the reference configuration `pose`, before initial angles) and force
// elements. Returns the initial angle of each joint (rad; 0 where none is given).
std::vector<double> addJoints(const YamlDocument& doc, const std::map<std::string, int>& index,
                              const BodyMarkers& markers, const std::vector<InitialPose>& pose,
                              MultibodySystem& sys);
void addForceElements(const YamlDocument& doc, const std::map<std::string, int>& index,
                      const BodyMarkers& markers, const std::vector<InitialPose>& pose,
                      MultibodySystem& sys);
void addSensors(const YamlDocument& doc, const std::map<std::string, int>& index,
                const BodyMarkers& markers, MultibodySystem& sys);

// Rotates, joint by joint in the scene's order, the bodies on end b's side of each revolute
// joint with an initial angle about its current axis through its current point (the bodies
// and joints must form a tree for this: a loop is reported).
void applyInitialAngles(const YamlDocument& doc, const MultibodySystem& sys,
                        const std::vector<double>& angles, std::vector<InitialPose>& pose);

// Refuses an initial state that violates a joint or whose joints are redundant, then
// projects y0 onto the constraints to round-off.
void checkInitialConstraints(const YamlDocument& doc, MultibodySystem& sys, Eigen::VectorXd& y0);

}  // namespace ffriga
