// Validation of YAML documents against a JSON Schema (the subset used in schemas/).
//
// The schemas in schemas/ are JSON Schema (draft 2020-12 vocabulary) and are the contract
// for the YAML input files; they are compiled into the programs, so a binary always checks
// against the schema it was built with. Supported keywords:
//   type (string or list of: object, array, number, integer, string, boolean, null),
//   properties, required, additionalProperties (false or a schema), items, minItems,
//   maxItems, minimum, maximum, exclusiveMinimum, exclusiveMaximum, enum, const,
//   $ref ("#/$defs/NAME" or "#/definitions/NAME"), oneOf (see below), and the annotations
//   title, description, default, examples, $schema, $id, $comment, x-unit.
// oneOf over object schemas that each fix one property with `const` (a discriminator such
// as geometry.type) selects the branch by that property, so errors come from the branch the
// user meant; other oneOf lists accept the first branch that validates.
// The first violation found is thrown as InputError "FILE:LINE: key 'a.b[2]': ..." .
#pragma once

#include <string>

#include <yaml-cpp/yaml.h>

#include "common/yaml_input.h"

namespace ffriga {

class JsonSchema {
 public:
  // Parses the schema text (JSON is YAML). Throws std::invalid_argument if it is malformed
  // or uses an unsupported keyword: that is a bug of the program, not of the user's input.
  JsonSchema(const std::string& text, const std::string& name);

  // Throws InputError on the first violation.
  void validate(const YamlDocument& doc) const;

  const std::string& name() const { return name_; }

 private:
  void check(const YamlDocument& doc, const YAML::Node& schema, const YAML::Node& node,
             const YAML::Node& parent, const std::string& key) const;
  YAML::Node resolve(const YAML::Node& schema) const;
  void checkKeywords(const YAML::Node& schema, const std::string& where) const;

  std::string name_;
  YAML::Node root_;
};

}  // namespace ffriga
