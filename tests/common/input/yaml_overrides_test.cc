// Command-line overrides (--set KEY=VALUE, common/input/yaml_overrides.h): paths through maps and
// lists, new keys, YAML values, and errors that name the override.
#include "common/input/yaml_overrides.h"

#include <catch2/catch.hpp>

using namespace ffriga;

namespace {

const char* kText = R"(name: s
contacts:
  - bodies: [a, b]
    penalty_factor: 1.0e17
refinement:
  insert_knots: [15, 24]
)";

std::string errorOf(const std::vector<std::string>& sets) {
  YamlDocument doc = parseYamlText(kText, "scene.yaml");
  try {
    applyOverrides(doc, sets);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("overrides: map keys, list indices, new keys, YAML values", "[overrides]") {
  YamlDocument doc = parseYamlText(kText, "scene.yaml");
  applyOverrides(doc, {"contacts.0.penalty_factor=3e17", "refinement.insert_knots.1=30",
                       "contacts.0.bodies=[c, d]", "integrator_note=hello",
                       "contacts.0.penalty_factor=4e17"});
  CHECK(doc.root["contacts"][0]["penalty_factor"].as<double>() == 4e17);  // the last wins
  CHECK(doc.root["refinement"]["insert_knots"][1].as<int>() == 30);
  CHECK(doc.root["refinement"]["insert_knots"][0].as<int>() == 15);
  CHECK(doc.root["contacts"][0]["bodies"][1].as<std::string>() == "d");
  CHECK(doc.root["integrator_note"].as<std::string>() == "hello");
  REQUIRE(doc.overrides.size() == 5);
  // An error about an overridden node names the override, not a line of the file.
  const std::string e = inputError(doc, doc.root["refinement"]["insert_knots"][1],
                                   "refinement.insert_knots[1]", "too many").what();
  CHECK(e == "scene.yaml: --set 'refinement.insert_knots.1=30': key "
             "'refinement.insert_knots[1]': too many");
  const std::string inside = inputError(doc, doc.root["contacts"][0]["bodies"][0],
                                        "contacts[0].bodies[0]", "unknown body").what();
  CHECK(inside.find("--set 'contacts.0.bodies=[c, d]'") != std::string::npos);
  // Other nodes keep their line.
  const std::string line = inputError(doc, doc.root["name"], "name", "bad").what();
  CHECK(line == "scene.yaml:1: key 'name': bad");
  CHECK(overridesFromText(overridesText({"a=1", "b.0=x"})) ==
        std::vector<std::string>{"a=1", "b.0=x"});
}

TEST_CASE("overrides: bad keys and values are input errors naming the override", "[overrides]") {
  CHECK(errorOf({"penalty_factor"}).find("scene.yaml: --set 'penalty_factor': expected "
                                         "KEY=VALUE") == 0);
  CHECK(errorOf({"nosuch.key=1"}).find("there is no key 'nosuch' in the file") !=
        std::string::npos);
  CHECK(errorOf({"contacts.3.penalty_factor=1"}).find("'contacts' is a list of 1 items: "
                                                      "expected an index 0..0, found '3'") !=
        std::string::npos);
  CHECK(errorOf({"name.first=1"}).find("'name' is s, not a mapping or a list") !=
        std::string::npos);
  CHECK(errorOf({"contacts..x=1"}).find("empty component") != std::string::npos);
  CHECK(errorOf({"name=[1, 2"}).find("the value is not valid YAML") != std::string::npos);
}

TEST_CASE("nodeAt and inputErrorAt: errors found after parsing name the key's line",
          "[yaml][errors]") {
  using namespace ffriga;
  YamlDocument doc = parseYamlText(
      "name: b\nreduction:\n  normal_modes: 5000\nbodies:\n  - {name: a}\n  - name: c\n", "b.yaml");
  CHECK(nodeAt(doc, "reduction.normal_modes").as<int>() == 5000);
  CHECK(nodeAt(doc, "bodies[1].name").as<std::string>() == "c");
  CHECK(yamlLine(nodeAt(doc, "bodies[1].name")) == 6);
  CHECK(!nodeAt(doc, "bodies[2].name"));
  CHECK(!nodeAt(doc, "reduction.frame"));
  CHECK(!nodeAt(doc, "name.inner"));
  CHECK(!doc.root["reduction"]["frame"]);  // the lookups inserted nothing
  const ParameterError e("reduction.normal_modes", "too many");
  CHECK(std::string(e.what()) == "key 'reduction.normal_modes': too many");
  CHECK(std::string(inputErrorAt(doc, e).what()) ==
        "b.yaml:3: key 'reduction.normal_modes': too many");
  // A key the file does not give: the file and the key, no line.
  CHECK(std::string(inputErrorAt(doc, ParameterError("reduction.frame", "x")).what()) ==
        "b.yaml: key 'reduction.frame': x");
  // An override names itself.
  applyOverrides(doc, {"reduction.normal_modes=7"});
  CHECK(std::string(inputErrorAt(doc, e).what()) ==
        "b.yaml: --set 'reduction.normal_modes=7': key 'reduction.normal_modes': too many");
}
