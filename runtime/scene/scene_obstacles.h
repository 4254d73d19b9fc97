// The rigid obstacles of a scene (schemas/scene.schema.json `obstacles`): planes and
// spheres fixed in space (runtime/contact/rigid_obstacle.h), by name, for the contact pairs
// that name them. Each error names the scene file, the YAML line and the key.
#pragma once

#include <map>
#include <string>

#include "common/input/yaml_input.h"
#include "runtime/contact/rigid_obstacle.h"

namespace ffriga {

// The obstacles by name. Bad input: a plane normal of zero length; in an axisymmetric scene
// a plane not normal to the axis (y) or a finite plane or sphere not centred on it.
std::map<std::string, RigidObstacle> readObstacles(const YamlDocument& doc, bool axisymmetric);

}  // namespace ffriga
