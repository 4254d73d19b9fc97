// Loading YAML input files and reporting errors in them.
//
// Every error about user input names the file, the YAML line (1-based) and the key path
// ("geometry.radius", "refinement.insert_knots[1]"), says what was expected and what was
// found, and is thrown as InputError (exit code 2).
#pragma once

#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "common/base/error.h"

namespace ffriga {

// A command-line override applied to a document (common/input/yaml_overrides.h): its text
// "KEY=VALUE" and the node it put into the tree (errors about it name the override).
struct YamlOverride {
  std::string text;  // KEY=VALUE
  std::string key;   // KEY, dotted (list indices as components)
  YAML::Node node;
};

// A property that a schema's `default` put into a document (JsonSchema::applyDefaults): its
// key path, the default as the schema writes it and the node it put into the tree (errors
// about it name the default instead of a line).
struct YamlDefault {
  std::string key;   // as errors name it: "integrator.rtol", "bodies[0].position"
  std::string text;  // the schema's value, JSON: 1e-06, [0, 0, 0], "structured", {}
  YAML::Node node;
};

struct YamlDocument {
  std::string path;  // as given by the user
  std::string text;  // the file's contents, kept for provenance
  YAML::Node root;
  std::vector<YamlOverride> overrides;  // --set, in order
  std::vector<YamlDefault> defaults;    // inserted by JsonSchema::applyDefaults, in order
};

// Reads and parses a YAML file. Throws InputError if the file cannot be read, is not valid
// YAML, or is empty.
YamlDocument loadYamlFile(const std::string& path);
// Parses YAML text that came from `path` (used by tests and for embedded documents).
YamlDocument parseYamlText(const std::string& text, const std::string& path);

// 1-based line of a node, 0 if unknown.
int yamlLine(const YAML::Node& node);

// "FILE:LINE: key 'KEY': MESSAGE" as an InputError; for a node an override put into the
// tree (or one inside it): "FILE: --set 'KEY=VALUE': key 'KEY': MESSAGE"; for a node a
// schema default put there (or one inside it): "FILE: key 'KEY' (schema default V): MESSAGE".
InputError inputError(const YamlDocument& doc, const YAML::Node& node, const std::string& key,
                      const std::string& message);

// The node at key path `key` ("reduction.normal_modes", "bodies[1].name"), undefined if the
// document has none.
YAML::Node nodeAt(const YamlDocument& doc, const std::string& key);
// inputError() for a ParameterError found after parsing: the file, the key's line (if the
// file gives the key) and the key.
InputError inputErrorAt(const YamlDocument& doc, const ParameterError& e);

// Whether `node` is, or lies inside, a value that JsonSchema::applyDefaults inserted (not one
// the file or an override gave): checks that forbid a key in some cases must not fire on a
// default the schema gives for every case (frozen on a rigid body, initial_angle on a joint
// that is not revolute, damping on a hertz_contact force element).
bool isSchemaDefault(const YamlDocument& doc, const YAML::Node& node);
// Whether the file or an override gave `node` (it exists and is no schema default).
inline bool isGiven(const YamlDocument& doc, const YAML::Node& node) {
  return node && !isSchemaDefault(doc, node);
}

// Human-readable rendering of a scalar or the kind of a collection, for "found ..." parts.
std::string describeNode(const YAML::Node& node);

// Typed access to a validated document. The key must exist and have the right type (the
// schema has checked); a failed conversion still reports file, line and key.
double getDouble(const YamlDocument& doc, const YAML::Node& node, const std::string& key);
int getInt(const YamlDocument& doc, const YAML::Node& node, const std::string& key);
bool getBool(const YamlDocument& doc, const YAML::Node& node, const std::string& key);
std::string getString(const YamlDocument& doc, const YAML::Node& node, const std::string& key);

// The enum value a word at `node` spells, through the enum's one spelling table
// (common/base/spelling.h), reached by an overload parseKind(std::string_view, E*) beside the
// enum. The schema's enum has checked the word: one the table lacks means the two are out
// of step, reported as an input error all the same.
template <class E>
E getKind(const YamlDocument& doc, const YAML::Node& node, const std::string& key) {
  E value{};
  const std::string text = getString(doc, node, key);
  if (!parseKind(text, &value))
    throw inputError(doc, node, key, "'" + text + "' is no value this program knows");
  return value;
}

}  // namespace ffriga
