#include "runtime/scene/scene_obstacles.h"

#include <cmath>

#include "runtime/scene/scene_values.h"

namespace ffriga {

namespace {

// A direction (a plane's normal, a cylinder's axis): any nonzero finite vector.
Eigen::Vector3d readDirection(const YamlDocument& doc, const YAML::Node& node,
                              const std::string& key) {
  const Eigen::Vector3d v = vector3(doc, node, key);
  const double length = v.norm();
  if (!(length > 0.0) || !std::isfinite(length))
    throw inputError(doc, node, key,
                     Str() << "expected a nonzero direction, found (" << v.transpose() << ")");
  return v;
}

RigidObstacle readPlane(const YamlDocument& doc, const YAML::Node& P, const std::string& name,
                        const std::string& k) {
  const Eigen::Vector3d point = vector3(doc, P["point"], k + ".point");
  const Eigen::Vector3d normal = readDirection(doc, P["normal"], k + ".normal");
  const double radius = doubleOr(doc, P["radius"], k + ".radius", 0.0);
  return RigidObstacle::plane(name, point, normal, radius);
}

RigidObstacle readSphere(const YamlDocument& doc, const YAML::Node& S, const std::string& name,
                         const std::string& k) {
  const Eigen::Vector3d centre = vector3(doc, S["centre"], k + ".centre");
  return RigidObstacle::sphere(name, centre, getDouble(doc, S["radius"], k + ".radius"));
}

RigidObstacle readCylinder(const YamlDocument& doc, const YAML::Node& C, const std::string& name,
                           const std::string& k) {
  const Eigen::Vector3d point = vector3(doc, C["point"], k + ".point");
  const Eigen::Vector3d axis = readDirection(doc, C["axis"], k + ".axis");
  return RigidObstacle::cylinder(name, point, axis, getDouble(doc, C["radius"], k + ".radius"));
}

// The key of obstacle O's shape ("plane", "sphere" or "cylinder"; the schema requires one).
std::string shapeKey(const YAML::Node& O) {
  for (const char* key : {"plane", "sphere", "cylinder"})
    if (O[key]) return key;
  return "sphere";
}

}  // namespace

std::map<std::string, RigidObstacle> readObstacles(const YamlDocument& doc, bool axisymmetric) {
  std::map<std::string, RigidObstacle> out;
  const YAML::Node obstacles = doc.root["obstacles"];
  for (std::size_t o = 0; obstacles && o < obstacles.size(); ++o) {
    const YAML::Node O = obstacles[o];
    const std::string k = Str() << "obstacles[" << o << "]";
    const std::string name = getString(doc, O["name"], k + ".name");
    const std::string shape = shapeKey(O);
    const std::string ks = k + "." + shape;
    RigidObstacle obstacle = shape == "plane"    ? readPlane(doc, O[shape], name, ks)
                             : shape == "sphere" ? readSphere(doc, O[shape], name, ks)
                                                 : readCylinder(doc, O[shape], name, ks);
    if (axisymmetric && !obstacle.axisymmetric())
      throw inputError(doc, O[shape], ks,
                       shape == "plane"
                           ? "an axisymmetric scene needs a plane normal to its axis (normal "
                             "(0, +-1, 0)), finite ones centred on it (point (0, y, 0))"
                       : shape == "sphere"
                           ? "an axisymmetric scene needs a sphere centred on its axis (centre "
                             "(0, y, 0))"
                           : "an axisymmetric scene needs a cylinder about its axis (point "
                             "(0, y, 0), axis (0, +-1, 0))");
    out.emplace(name, std::move(obstacle));
  }
  return out;
}

}  // namespace ffriga
