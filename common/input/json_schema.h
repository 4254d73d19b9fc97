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
// user meant; other oneOf lists must have exactly one branch that validates.
// The first violation found is thrown as InputError "FILE:LINE: key 'a.b[2]': ..." .
//
// Defaults: applyDefaults() completes a document that passed validate() with the schema's
// `default`s, so that the programs need not repeat them. Every property the document lacks
// whose schema (beside a $ref or behind it) has a `default` is inserted into the mapping the
// schema describes: at every level of present mappings, into every item of a list (its
// `items`), into the branch of a oneOf that applies (the one its discriminator selects, else
// the one that validates: chosen before anything is inserted at that level), and into the
// inserted values themselves (an absent object with `default: {}` is inserted, then filled
// with its own properties' defaults). Present keys are never changed. The inserted value is
// a deep copy of the schema's JSON as YAML nodes, scalars with their text and quoting (1e-06
// reads back as the double 1e-6, "structured" stays a string), without a line; each
// insertion is recorded in doc.defaults (key path, the default's JSON, the node), and an
// error about such a node, or one inside it, reads "FILE: key 'K' (schema default V): ..."
// (inputError, yaml_input.h). A mapping that YAML aliases share is filled at each place that
// reaches it, so its defaults show at all of them.
//
// Held to the official JSON-Schema-Test-Suite (Debian json-schema-test-suite, draft 7: the
// newest Debian 12 ships; for our keywords it agrees with 2020-12) by
// tests/common/input/json_schema_suite_test.cc, for every keyword implemented here; what is not
// implemented is listed there with the reason.
//
// Why not valijson (Debian 12: libvalijson-dev 1.0, evaluated 2026-12): its yaml-cpp adapter
// does not compile against its Validator (forward-only iterators; fixed upstream, PR #175)
// and ignores YAML quoting, so "1" and 1 are the same value: with weak types every scalar
// is a string and maybe a number (suite type.json 52/59), with strong types no number
// matches. Its errors carry only a path of strings ("<root>[geometry][radius]", an index
// and a key both "[0]"), no node or mark, so FILE:LINE would mean walking the tree again;
// messages lack the unit and the value found ("Expected number greater than 0.000000"),
// and one wrong value in a oneOf yields ~24 errors, one per branch. Drafts 3/4/7 only.
// We keep this validator.
#pragma once

#include <string>

#include <yaml-cpp/yaml.h>

#include "common/input/yaml_input.h"

namespace ffriga {

class JsonSchema {
 public:
  // Parses the schema text (JSON is YAML). Throws std::invalid_argument if it is malformed
  // or uses an unsupported keyword: that is a bug of the program, not of the user's input.
  JsonSchema(const std::string& text, const std::string& name);

  // Throws InputError on the first violation.
  void validate(const YamlDocument& doc) const;

  // Inserts the schema's defaults for absent properties into a document that passed
  // validate() and records them in doc.defaults (see above).
  void applyDefaults(YamlDocument& doc) const;

  const std::string& name() const { return name_; }

 private:
  // check() runs the phases below in turn on `node` (the value at `key`; `parent` carries
  // the line when the node is absent).
  void check(const YamlDocument& doc, const YAML::Node& schema, const YAML::Node& node,
             const YAML::Node& parent, const std::string& key) const;
  void checkArray(const YamlDocument& doc, const YAML::Node& schema, const YAML::Node& node,
                  const YAML::Node& where, const std::string& key) const;
  void checkUnknownKeys(const YamlDocument& doc, const YAML::Node& schema, const YAML::Node& node,
                        const std::string& key) const;
  void checkRequired(const YamlDocument& doc, const YAML::Node& schema, const YAML::Node& node,
                     const YAML::Node& where, const std::string& key) const;
  void checkProperties(const YamlDocument& doc, const YAML::Node& schema, const YAML::Node& node,
                       const std::string& key) const;
  void checkOneOf(const YamlDocument& doc, const YAML::Node& one, const YAML::Node& node,
                  const YAML::Node& parent, const std::string& key) const;
  void checkExactlyOne(const YamlDocument& doc, const YAML::Node& one, const YAML::Node& node,
                       const YAML::Node& parent, const std::string& key) const;
  std::string discriminatorOf(const YAML::Node& one) const;
  YAML::Node branchFor(const YAML::Node& one, const std::string& discriminator,
                       const YAML::Node& tag) const;
  std::string branchValues(const YAML::Node& one, const std::string& discriminator) const;

  // applyDefaults() on `node`, the value at `key` that `schema` describes.
  void fillDefaults(YamlDocument& doc, const YAML::Node& schema, const YAML::Node& node,
                    const std::string& key) const;
  void fillProperties(YamlDocument& doc, const YAML::Node& schema, const YAML::Node& node,
                      const std::string& key) const;
  void insertDefault(YamlDocument& doc, const YAML::Node& propertySchema, const YAML::Node& map,
                     const std::string& name, const std::string& key) const;
  YAML::Node chosenBranch(const YamlDocument& doc, const YAML::Node& one, const YAML::Node& node,
                          const std::string& key) const;

  YAML::Node resolve(const YAML::Node& schema) const;
  void checkKeywords(const YAML::Node& schema, const std::string& where) const;

  std::string name_;
  YAML::Node root_;
};

}  // namespace ffriga
