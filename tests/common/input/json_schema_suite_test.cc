// Conformance of common/input/json_schema.h with the official JSON-Schema-Test-Suite.
//
// Every test case of the suite files for the keywords our validator implements and our
// schemas use is run through JsonSchema (schema text as given, instance parsed with
// parseYamlText), and the verdict must equal the suite's "valid". Rejections must also keep
// the "FILE:LINE: ..." form of our messages.
//
// Draft: schemas/*.schema.json declare draft 2020-12, but Debian 12's json-schema-test-suite
// (2.0.0) stops at draft 7, so the draft-7 files are used. For these keywords the two drafts
// agree except for (a) the array form of "items" (draft 7 tuples; 2020-12 calls them
// prefixItems, which we do not support: skipped) and (b) keywords next to "$ref" (draft 7
// ignores them, 2020-12 applies them; our validator ignores them and our schemas put only
// annotations there, so both readings give the same verdicts).
//
// The suite is found in $JSON_SCHEMA_TEST_SUITE_DIR, else FFRIGA_JSON_SCHEMA_SUITE_DIR (a
// compile definition), else Debian's /usr/share/json-schema-test-suite (package
// json-schema-test-suite, in .ci/install-deps). Run with -s to see the per-keyword figures;
// a failure names the suite file, the group and test descriptions, the schema and the data.
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>

#include <catch2/catch.hpp>

#include "common/input/json_schema.h"
#include "common/input/yaml_input.h"

using namespace ffriga;

#ifndef FFRIGA_JSON_SCHEMA_SUITE_DIR
#define FFRIGA_JSON_SCHEMA_SUITE_DIR "/usr/share/json-schema-test-suite"
#endif

namespace {

// A suite case our validator does not support on purpose. An empty `test` skips every test
// of the group (the schema itself is out of scope).
struct Skip {
  const char* file;
  const char* group;
  const char* test;
  const char* reason;
};

const Skip kSkips[] = {
    {"additionalProperties.json",
     "additionalProperties being false does not allow other properties", "",
     "the schema uses patternProperties (not supported)"},
    {"additionalProperties.json", "non-ASCII pattern with additionalProperties", "",
     "the schema uses patternProperties (not supported)"},
    {"properties.json", "properties, patternProperties, additionalProperties interaction", "",
     "the schema uses patternProperties (not supported)"},
    {"items.json", "an array of schemas for items", "",
     "draft-7 tuple form of items; 2020-12 spells it prefixItems (not supported)"},
    {"items.json", "items with boolean schemas", "",
     "draft-7 tuple form of items; 2020-12 spells it prefixItems (not supported)"},
    {"oneOf.json", "oneOf with base schema", "",
     "the branches use minLength/maxLength (not supported)"},
    {"default.json", "invalid string value for default", "",
     "the schema uses minLength (not supported)"},
    {"ref.json", "root pointer ref", "", "$ref \"#\": only #/$defs/NAME, #/definitions/NAME"},
    {"ref.json", "relative pointer ref to object", "",
     "$ref \"#/properties/foo\": only #/$defs/NAME, #/definitions/NAME"},
    {"ref.json", "relative pointer ref to array", "",
     "$ref \"#/items/0\" and tuple items: only #/$defs/NAME, #/definitions/NAME"},
    {"ref.json", "escaped pointer ref", "",
     "$ref to escaped pointers outside $defs (~0, ~1, %25): only #/$defs/NAME"},
    {"ref.json", "remote ref, containing refs itself", "", "remote $ref (the draft-7 metaschema)"},
    {"ref.json", "Recursive references between schemas", "", "$id-relative $ref ('node', 'tree')"},
    {"definitions.json", "valid definition", "", "remote $ref (the draft-7 metaschema)"},
    {"definitions.json", "invalid definition", "", "remote $ref (the draft-7 metaschema)"},
};

const Skip* findSkip(const std::string& file, const std::string& group, const std::string& test) {
  for (const Skip& s : kSkips) {
    if (file == s.file && group == s.group && (*s.test == '\0' || test == s.test)) return &s;
  }
  return nullptr;
}

std::string suiteRoot() {
  const char* env = std::getenv("JSON_SCHEMA_TEST_SUITE_DIR");
  return env && *env ? env : FFRIGA_JSON_SCHEMA_SUITE_DIR;
}

std::string quoted(const std::string& s) {
  Str out;
  out << '"';
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out << '\\' << c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      const char* hex = "0123456789abcdef";
      out << "\\u00" << hex[(c >> 4) & 0xf] << hex[c & 0xf];
    } else {
      out << c;
    }
  }
  out << '"';
  return out;
}

// The JSON text of a node read from a JSON file: scalars as written (strings quoted), so
// that the validator sees the same types as in the suite.
std::string toJson(const YAML::Node& n) {
  if (n.IsNull()) return "null";
  if (n.IsScalar()) return n.Tag() == "!" ? quoted(n.Scalar()) : n.Scalar();
  Str out;
  bool first = true;
  if (n.IsSequence()) {
    out << "[";
    for (const auto& x : n) out << (first ? "" : ", ") << toJson(x), first = false;
    out << "]";
  } else {
    out << "{";
    for (const auto& kv : n) {
      out << (first ? "" : ", ") << quoted(kv.first.Scalar()) << ": " << toJson(kv.second);
      first = false;
    }
    out << "}";
  }
  return out;
}

struct Verdict {
  bool valid = false;
  bool error = false;   // no verdict: the instance did not parse, or the validator threw
                        // something other than InputError
  std::string message;  // why it rejected the instance, or what it threw
};

// The instance is wrapped in a mapping so that `null` is a document too (parseYamlText
// refuses empty documents); the validator sees the wrapped value as the document root.
Verdict judge(const std::string& schemaJson, const std::string& dataJson,
              const std::string& label) {
  Verdict v;
  YamlDocument doc;
  try {
    const YamlDocument wrapped = parseYamlText("{\"instance\": " + dataJson + "}", label);
    doc.path = wrapped.path;
    doc.text = wrapped.text;
    const YAML::Node& root = wrapped.root;
    doc.root.reset(root["instance"]);
  } catch (const std::exception& e) {
    v.error = true;
    v.message = std::string("parseYamlText refused the instance: ") + e.what();
    return v;
  }
  try {
    const JsonSchema schema(schemaJson, label);
    schema.validate(doc);
    v.valid = true;
  } catch (const InputError& e) {
    v.message = e.what();
  } catch (const std::exception& e) {
    v.error = true;
    v.message = e.what();
  }
  return v;
}

struct Tally {
  int passed = 0, failed = 0, skipped = 0;
};

}  // namespace

TEST_CASE("JSON-Schema-Test-Suite (draft 7) for the keywords we implement", "[schema][suite]") {
  // Checked before GENERATE, so that a missing suite is reported once, not per keyword.
  const std::string dir = suiteRoot() + "/tests/draft7";
  if (!std::filesystem::is_directory(dir)) {
    FAIL("JSON-Schema-Test-Suite not found: no directory "
         << dir << ". Install it with `apt-get install json-schema-test-suite` (Debian, see "
         << ".ci/install-deps), or set JSON_SCHEMA_TEST_SUITE_DIR to a checkout of "
         << "https://github.com/json-schema-org/JSON-Schema-Test-Suite");
  }
  // The keywords of common/input/json_schema.h that schemas/ use ($ref and $defs: ref.json,
  // definitions.json). anyOf, pattern, minLength, ... are not implemented, so not run.
  const std::string keyword =
      GENERATE(as<std::string>{}, "type", "properties", "required", "additionalProperties", "items",
               "minItems", "maxItems", "minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum",
               "enum", "const", "oneOf", "default", "ref", "definitions");
  const std::string file = keyword + ".json";
  const std::string path = dir + "/" + file;
  REQUIRE(std::filesystem::is_regular_file(path));
  const YamlDocument suite = loadYamlFile(path);
  REQUIRE(suite.root.IsSequence());

  Tally tally;
  std::set<const Skip*> used;
  for (const auto& group : suite.root) {
    const std::string groupName = group["description"].Scalar();
    const std::string schemaJson = toJson(group["schema"]);
    for (const auto& test : group["tests"]) {
      const std::string testName = test["description"].Scalar();
      if (const Skip* s = findSkip(file, groupName, testName)) {
        used.insert(s);
        ++tally.skipped;
        continue;
      }
      const bool expected = test["valid"].as<bool>();
      const std::string dataJson = toJson(test["data"]);
      const Verdict v = judge(schemaJson, dataJson, file);
      // A rejection must still name the file and the line (the instance is on line 1).
      const bool wellFormed = v.valid || v.error || v.message.rfind(file + ":1: ", 0) == 0;
      if (!v.error && v.valid == expected && wellFormed) {
        ++tally.passed;
        continue;
      }
      ++tally.failed;
      Str why;
      if (v.error) {
        why << "no verdict: " << v.message;
      } else if (v.valid != expected) {
        why << (expected ? "expected valid, rejected: " + v.message
                         : std::string("expected invalid, accepted"));
      } else {
        why << "rejected without FILE:LINE: " << v.message;
      }
      FAIL_CHECK(path << "\n  group:  " << groupName << "\n  test:   " << testName << "\n  schema: "
                      << schemaJson << "\n  data:   " << dataJson << "\n  " << why.str());
    }
  }

  for (const Skip& s : kSkips) {
    if (file == s.file && !used.count(&s)) {
      FAIL_CHECK("skip list entry matches no case of " << path << ": group '" << s.group
                                                       << "' (suite version changed?)");
    }
  }
  INFO(file << ": " << tally.passed << " passed, " << tally.failed << " failed, " << tally.skipped
            << " skipped");
  CHECK(tally.failed == 0);
  CHECK(tally.passed + tally.failed + tally.skipped > 0);  // the file has cases at all
}
