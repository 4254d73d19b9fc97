// Typed values of a validated scene document (the schema has checked types and ranges):
// vectors and matrices of numbers, each entry read with its key for error messages.
#pragma once

#include <string>

#include <Eigen/Dense>

#include "common/input/yaml_input.h"

namespace ffriga {

// The list of numbers at `node` (key[i] in messages).
inline Eigen::VectorXd numbers(const YamlDocument& doc, const YAML::Node& node,
                               const std::string& key) {
  Eigen::VectorXd v(node.size());
  for (std::size_t i = 0; i < node.size(); ++i)
    v(i) = getDouble(doc, node[i], Str() << key << "[" << i << "]");
  return v;
}

// Keys whose schema has no default (the value when absent depends on the scene: a body's
// mode count, "automatic" for a search margin): `fallback` when absent.
inline Eigen::VectorXd vectorOr(const YamlDocument& doc, const YAML::Node& node,
                                const std::string& key, const Eigen::VectorXd& fallback) {
  return node ? numbers(doc, node, key) : fallback;
}

inline double doubleOr(const YamlDocument& doc, const YAML::Node& node, const std::string& key,
                       double fallback) {
  return node ? getDouble(doc, node, key) : fallback;
}

inline Eigen::Vector3d vector3(const YamlDocument& doc, const YAML::Node& node,
                               const std::string& key) {
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v(i) = getDouble(doc, node[i], Str() << key << "[" << i << "]");
  return v;
}

inline Eigen::Matrix3d matrix3(const YamlDocument& doc, const YAML::Node& node,
                               const std::string& key) {
  Eigen::Matrix3d M;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      M(i, j) = getDouble(doc, node[i][j], Str() << key << "[" << i << "][" << j << "]");
  return M;
}

}  // namespace ffriga
