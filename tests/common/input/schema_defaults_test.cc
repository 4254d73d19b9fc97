// JsonSchema::applyDefaults: the schemas' `default`s inserted into validated documents, and
// errors about inserted nodes naming the default.
#include <cstdlib>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "common/input/json_schema.h"
#include "common/input/schemas.h"
#include "common/input/yaml_overrides.h"

using namespace ffriga;

namespace {

// Validates `yaml` against `schema`, applies the defaults and returns the document.
YamlDocument completed(const JsonSchema& schema, const std::string& yaml,
                       const std::string& path = "in.yaml") {
  YamlDocument doc = parseYamlText(yaml, path);
  schema.validate(doc);
  schema.applyDefaults(doc);
  return doc;
}

std::vector<std::string> defaultKeys(const YamlDocument& doc) {
  std::vector<std::string> keys;
  for (const YamlDefault& d : doc.defaults) keys.push_back(d.key);
  return keys;
}

using Keys = std::vector<std::string>;

const char* kNested = R"({
  "type": "object", "additionalProperties": false,
  "properties": {
    "a": {"type": "object", "additionalProperties": false, "properties": {
      "x": {"type": "number", "default": 1.5},
      "s": {"type": "string", "default": "plain"},
      "inner": {"type": "object", "properties": {"deep": {"type": "integer", "default": 7}}}
    }},
    "top": {"type": "boolean", "default": true},
    "v": {"$ref": "#/$defs/vector", "default": [0, 0.25, 1e-06]}
  },
  "$defs": {"vector": {"type": "array", "items": {"type": "number"}}}
})";

}  // namespace

TEST_CASE("defaults: nested objects get theirs, present keys are kept", "[schema][defaults]") {
  const JsonSchema schema(kNested, "nested");
  const YamlDocument doc = completed(schema, "a:\n  s: given\n  inner: {}\n");
  CHECK(doc.root["a"]["x"].as<double>() == 1.5);
  CHECK(doc.root["a"]["s"].as<std::string>() == "given");
  CHECK(doc.root["a"]["inner"]["deep"].as<int>() == 7);
  CHECK(doc.root["top"].as<bool>());
  REQUIRE(doc.root["v"].IsSequence());
  CHECK(doc.root["v"].size() == 3);
  CHECK(doc.root["v"][1].as<double>() == 0.25);
  CHECK(doc.root["v"][2].as<double>() == 1e-6);
  CHECK(defaultKeys(doc) == Keys{"a.x", "a.inner.deep", "top", "v"});
  CHECK(doc.defaults[0].text == "1.5");
  CHECK(doc.defaults[3].text == "[0, 0.25, 1e-06]");
  // An absent object without a default stays absent; nothing is overwritten.
  const YamlDocument full =
      completed(schema, "a: {x: 2, s: mine, inner: {deep: 1}}\ntop: false\nv: [1]\n");
  CHECK(full.defaults.empty());
  CHECK(full.root["a"]["x"].as<double>() == 2.0);
  CHECK(full.root["v"].size() == 1);
  CHECK(completed(schema, "top: false\n").defaults.size() == 1);  // v only: no 'a'
  // The completed document still validates.
  CHECK_NOTHROW(schema.validate(doc));
}

TEST_CASE("defaults: strings stay strings, numbers read back as the schema's double",
          "[schema][defaults]") {
  const JsonSchema schema(R"({"type": "object", "properties": {
    "name": {"type": "string", "default": "1.0"},
    "tiny": {"type": "number", "default": 1e-12},
    "odd": {"type": "number", "default": 0.1},
    "big": {"type": "number", "default": 3e17}
  }})",
                          "strings");
  const YamlDocument doc = completed(schema, "{}\n");
  // A quoted default stays quoted: the schema check sees a string, not the number 1.0.
  CHECK(doc.root["name"].Tag() == "!");
  CHECK(describeNode(doc.root["name"]) == "\"1.0\"");
  CHECK_NOTHROW(schema.validate(doc));
  CHECK(doc.root["tiny"].as<double>() == 1e-12);
  CHECK(doc.root["odd"].as<double>() == 0.1);
  CHECK(doc.root["big"].as<double>() == 3e17);
  CHECK(doc.defaults[0].text == "\"1.0\"");
}

TEST_CASE("defaults: into every item of a list", "[schema][defaults]") {
  const JsonSchema schema(R"({"type": "object", "properties": {
    "lines": {"type": "array", "items": {"type": "object", "required": ["name"],
      "properties": {"name": {"type": "string"}, "points": {"type": "integer", "default": 101}}}}
  }})",
                          "items");
  const YamlDocument doc =
      completed(schema, "lines:\n  - {name: a}\n  - {name: b, points: 3}\n  - {name: c}\n");
  CHECK(doc.root["lines"][0]["points"].as<int>() == 101);
  CHECK(doc.root["lines"][1]["points"].as<int>() == 3);
  CHECK(doc.root["lines"][2]["points"].as<int>() == 101);
  CHECK(defaultKeys(doc) == Keys{"lines[0].points", "lines[2].points"});
}

TEST_CASE("defaults: the oneOf branch that applies", "[schema][defaults]") {
  SECTION("discriminated: the branch the tag selects") {
    const JsonSchema schema(R"({"type": "object", "properties": {"shape": {
      "type": "object", "required": ["type"],
      "oneOf": [
        {"additionalProperties": false, "properties": {"type": {"const": "ball"},
          "radius": {"type": "number", "default": 1}}},
        {"additionalProperties": false, "properties": {"type": {"const": "box"},
          "size": {"$ref": "#/$defs/three", "default": [2, 2, 2]}}}
      ]}},
      "$defs": {"three": {"type": "array", "items": {"type": "number"}}}})",
                            "discriminated");
    const YamlDocument ball = completed(schema, "shape: {type: ball}\n");
    CHECK(ball.root["shape"]["radius"].as<double>() == 1.0);
    CHECK(!ball.root["shape"]["size"]);
    const YamlDocument box = completed(schema, "shape: {type: box}\n");
    CHECK(!box.root["shape"]["radius"]);
    CHECK(box.root["shape"]["size"][2].as<double>() == 2.0);
    CHECK(defaultKeys(box) == Keys{"shape.size"});
    CHECK_NOTHROW(schema.validate(box));
  }
  SECTION("not discriminated: the branch that validates") {
    const JsonSchema schema(R"({"type": "object", "properties": {"q": {"oneOf": [
      {"type": "boolean", "const": false},
      {"type": "object", "additionalProperties": false,
       "properties": {"hz": {"type": "number", "default": 50}}}
    ]}}})",
                            "plain");
    CHECK(completed(schema, "q: false\n").defaults.empty());
    const YamlDocument doc = completed(schema, "q: {}\n");
    CHECK(doc.root["q"]["hz"].as<double>() == 50.0);
    CHECK(defaultKeys(doc) == Keys{"q.hz"});
  }
}

TEST_CASE("defaults: an absent object with a default is inserted, then filled",
          "[schema][defaults]") {
  const JsonSchema schema(R"({"type": "object", "properties": {
    "o": {"type": "object", "default": {}, "properties": {
      "n": {"type": "integer", "default": 3},
      "p": {"type": "object", "default": {"given": 1}, "properties": {
        "given": {"type": "integer"}, "m": {"type": "string", "default": "x"}}}}}
  }})",
                          "object");
  const YamlDocument doc = completed(schema, "{}\n");
  REQUIRE(doc.root["o"].IsMap());
  CHECK(doc.root["o"]["n"].as<int>() == 3);
  CHECK(doc.root["o"]["p"]["given"].as<int>() == 1);
  CHECK(doc.root["o"]["p"]["m"].as<std::string>() == "x");
  CHECK(defaultKeys(doc) == Keys{"o", "o.n", "o.p", "o.p.m"});
  CHECK(doc.defaults[0].text == "{}");
  CHECK(doc.defaults[2].text == "{\"given\": 1}");
  // The schema's own default is untouched (a copy went into the document).
  const YamlDocument again = completed(schema, "{}\n");
  CHECK(again.root["o"]["p"].size() == 2);
}

TEST_CASE("defaults: errors about an inserted node name the default", "[schema][defaults]") {
  const JsonSchema schema(kNested, "nested");
  YamlDocument doc = completed(schema, "a:\n  s: given\n", "f.yaml");
  CHECK(std::string(inputError(doc, doc.root["a"]["x"], "a.x", "too small").what()) ==
        "f.yaml: key 'a.x' (schema default 1.5): too small");
  CHECK(std::string(inputError(doc, doc.root["v"][2], "v[2]", "bad").what()) ==
        "f.yaml: key 'v[2]' (schema default [0, 0.25, 1e-06]): bad");
  CHECK(std::string(inputError(doc, doc.root["a"]["s"], "a.s", "bad").what()) ==
        "f.yaml:2: key 'a.s': bad");
  CHECK(std::string(inputError(doc, doc.root["a"], "a", "bad").what()) == "f.yaml:2: key 'a': bad");
  CHECK(isSchemaDefault(doc, doc.root["a"]["x"]));
  CHECK(isSchemaDefault(doc, doc.root["v"][2]));
  CHECK(!isSchemaDefault(doc, doc.root["a"]["s"]));
  CHECK(!isSchemaDefault(doc, doc.root["a"]));
  CHECK(!isSchemaDefault(doc, doc.root["nothing"]));
}

TEST_CASE("defaults: inside a mapping an override put there, the default is named",
          "[schema][defaults]") {
  const JsonSchema schema(kSceneSchema, "scene");
  YamlDocument doc = parseYamlText(
      "bodies: [{name: a, sid: a.sid.h5}]\nintegrator: {end_time: 1, output_interval: 0.1}\n",
      "scene.yaml");
  applyOverrides(doc, {"integrator={end_time: 2, output_interval: 0.5}"});
  schema.validate(doc);
  schema.applyDefaults(doc);
  const YAML::Node integrator = doc.root["integrator"];
  CHECK(std::string(inputError(doc, integrator["rtol"], "integrator.rtol", "bad").what()) ==
        "scene.yaml: key 'integrator.rtol' (schema default 1e-06): bad");
  CHECK(std::string(inputError(doc, integrator["end_time"], "integrator.end_time", "bad").what()) ==
        "scene.yaml: --set 'integrator={end_time: 2, output_interval: 0.5}': key "
        "'integrator.end_time': bad");
}

TEST_CASE("defaults of the real scene schema", "[schema][defaults][scene]") {
  const JsonSchema schema(kSceneSchema, "scene");
  const YamlDocument doc = completed(schema,
                                     "bodies:\n"
                                     "  - {name: a, sid: a.sid.h5}\n"
                                     "  - {name: b, rigid: {mass: 1, inertia: [[1, 0, 0], [0, 1, "
                                     "0], [0, 0, 1]]}, position: [0, 1, 0]}\n"
                                     "contacts: [{bodies: [a, b], penalty_factor: 1e15}]\n"
                                     "integrator: {end_time: 1.0e-4, output_interval: 1.0e-6}\n"
                                     "outputs: {visualisation: {interval: 1.0e-5}}\n",
                                     "scene.yaml");
  const YAML::Node integrator = doc.root["integrator"];
  CHECK(integrator["rtol"].as<double>() == 1e-6);
  CHECK(integrator["atol_position"].as<double>() == 1e-12);
  CHECK(integrator["atol_velocity"].as<double>() == 1e-8);
  CHECK(integrator["atol_rotation"].as<double>() == 1e-10);
  CHECK(integrator["atol_angular_velocity"].as<double>() == 1e-6);
  CHECK(integrator["linear_solver"].as<std::string>() == "structured");
  CHECK(integrator["max_order"].as<int>() == 3);
  CHECK(!integrator["max_step"]);  // no default: "unlimited"
  const YAML::Node outputs = doc.root["outputs"];
  CHECK(outputs["flush_interval"].as<double>() == 2.0);
  CHECK(outputs["flush_rows"].as<int>() == 16);
  CHECK(outputs["progress_interval"].as<double>() == 1.0);
  CHECK(outputs["visualisation"]["magnification"].as<double>() == 1.0);
  CHECK(outputs["visualisation"]["revolve"].as<int>() == 0);
  CHECK(doc.root["gravity"].size() == 3);
  CHECK(doc.root["static_preload"].as<bool>() == false);
  const YAML::Node a = doc.root["bodies"][0];
  CHECK(a["frozen"].as<bool>() == false);
  CHECK(a["orientation"][0].as<double>() == 1.0);
  CHECK(a["velocity"][2].as<double>() == 0.0);
  CHECK(!a["q"]);
  const YAML::Node b = doc.root["bodies"][1];
  CHECK(b["position"][1].as<double>() == 1.0);  // given
  CHECK(b["rigid"]["centre_of_mass"].size() == 3);
  CHECK(doc.root["contacts"][0]["both_roles"].as<bool>() == true);
  // Keys the program forbids in some cases get their default everywhere: a rigid body's
  // frozen (scene.cc: "'frozen' is for SID bodies"); isSchemaDefault tells them apart.
  CHECK(b["frozen"].as<bool>() == false);
  CHECK(isSchemaDefault(doc, b["frozen"]));
  CHECK_NOTHROW(schema.validate(doc));
  // Without outputs, its default {} is inserted and completed in turn.
  const YamlDocument bare = completed(
      schema,
      "bodies: [{name: a, sid: a.sid.h5}]\nintegrator: {end_time: 1, output_interval: 1}\n");
  REQUIRE(bare.root["outputs"].IsMap());
  CHECK(bare.root["outputs"]["flush_rows"].as<int>() == 16);
  CHECK(!bare.root["outputs"]["visualisation"]);
  CHECK(bare.root["integrator"]["rtol"].as<double>() == 1e-6);
}

TEST_CASE("defaults of the real body schema", "[schema][defaults][body]") {
  const JsonSchema schema(kBodySchema, "body");
  const YamlDocument doc =
      completed(schema,
                "name: t\nmodel: axisymmetric\n"
                "material: {youngs_modulus: 2.11e11, poisson_ratio: 0.3, density: 7850}\n"
                "geometry: {type: half_disk, radius: 0.01}\n"
                "contact: {face: xi_max, region: [[0.0, 0.5]]}\n"
                "markers: [{name: m, parameters: [0.5, 0.5]}, {name: k, parameters: [0, 0], "
                "interface: true}]\n"
                "reduction: {normal_modes: 4}\n"
                "visualisation: {stress_lines: [{name: axis, from: [0, 0.01], to: [0, -0.01]}]}\n",
                "body.yaml");
  CHECK(doc.root["contact"]["name"].as<std::string>() == "contact");
  CHECK(doc.root["markers"][0]["interface"].as<bool>() == false);
  CHECK(doc.root["markers"][1]["interface"].as<bool>() == true);
  CHECK(doc.root["reduction"]["method"].as<std::string>() == "craig_bampton");
  CHECK(doc.root["reduction"]["normal_modes"].as<int>() == 4);
  CHECK(doc.root["reduction"]["frame"].as<std::string>() == "buckens");
  CHECK(doc.root["reduction"]["damping"].IsSequence());
  CHECK(doc.root["reduction"]["damping"].size() == 0);
  CHECK(doc.root["visualisation"]["stress_lines"][0]["points"].as<int>() == 101);
  CHECK(!doc.root["refinement"]);
  CHECK_NOTHROW(schema.validate(doc));
}

TEST_CASE("defaults of the real schemas read back as the schema's numbers", "[schema][defaults]") {
  // Every number a default inserts parses to the double strtod reads from the schema text.
  for (const char* text : {kSceneSchema, kBodySchema}) {
    const JsonSchema schema(text, "schema");
    const YamlDocument doc =
        text == kSceneSchema
            ? completed(schema,
                        "bodies: [{name: a, rigid: {mass: 1, inertia: [[1, 0, 0], [0, 1, 0], "
                        "[0, 0, 1]]}}]\njoints: [{type: revolute, a: {body: ground}, b: {body: "
                        "a, marker: m}}]\nforce_elements: [{type: spring_damper, a: {body: "
                        "ground}, b: {body: a, marker: m}}]\nintegrator: {end_time: 1, "
                        "output_interval: 1}\noutputs: {}\n")
            : completed(schema,
                        "name: t\nmodel: solid\n"
                        "material: {youngs_modulus: 1, poisson_ratio: 0.3, density: 1}\n"
                        "geometry: {type: sphere, radius: 0.01}\nreduction: {}\n");
    CHECK(doc.defaults.size() >= (text == kSceneSchema ? 14u : 4u));
    for (const YamlDefault& d : doc.defaults) {
      INFO(d.key << " = " << d.text);
      if (!d.node.IsScalar() || d.node.Tag() == "!") continue;
      double v = 0.0;
      if (!YAML::convert<double>::decode(d.node, v)) continue;  // true, false
      CHECK(v == std::strtod(d.text.c_str(), nullptr));
    }
  }
}
