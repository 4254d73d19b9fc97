// Command-line overrides of a YAML input (`--set KEY=VALUE`, repeatable, both programs):
// KEY is a dotted path into the document, map keys by name and list items by their
// 0-based index (`contacts.0.penalty_factor`, `refinement.insert_knots.1`); VALUE is YAML
// (`3e17`, `[2, 2]`, `{ratio: 1.0}`, a string). The last component may name a new key of a
// mapping (the schema then decides whether it is allowed); every other component must
// exist. Overrides apply in order, before the schema check, so that an overridden value is
// checked like the file's own; an error about it names the file and the override:
//
//   scene.yaml: --set 'contacts.0.penalty_factor=-1': key 'contacts[0].penalty_factor': ...
//
// exit code 2 (InputError). The programs record the overrides with their outputs
// (provenance) and a restart applies them again.
#pragma once

#include <string>
#include <vector>

#include "common/input/yaml_input.h"

namespace ffriga {

// Applies `sets` ("KEY=VALUE" each) to doc.root and records them in doc.overrides.
void applyOverrides(YamlDocument& doc, const std::vector<std::string>& sets);

// The overrides as recorded in output files: one "KEY=VALUE" per line ("" for none).
std::string overridesText(const std::vector<std::string>& sets);
std::vector<std::string> overridesFromText(const std::string& text);

}  // namespace ffriga
