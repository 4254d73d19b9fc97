#include "common/input/json_schema.h"

#include <catch2/catch.hpp>

#include "preproc/input/body_config.h"

using namespace ffriga;

namespace {

const char* kSchema = R"({
  "type": "object", "required": ["a"], "additionalProperties": false,
  "properties": {
    "a": {"type": "number", "exclusiveMinimum": 0, "x-unit": "m"},
    "b": {"type": "array", "minItems": 2, "items": {"type": "integer"}},
    "c": {"enum": ["x", "y"]},
    "d": {"$ref": "#/$defs/thing"},
    "e": {"oneOf": [{"type": "number", "exclusiveMinimum": 0}, {"const": "auto"}]},
    "f": {"oneOf": [{"enum": ["same", "plane"]}, {"$ref": "#/$defs/thing"}]}
  },
  "$defs": {"thing": {"type": "object", "properties": {"n": {"type": "string"}}}}
})";

std::string errorOf(const std::string& yaml) {
  const JsonSchema schema(kSchema, "test");
  try {
    schema.validate(parseYamlText(yaml, "in.yaml"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("schema validation reports file, line and key", "[schema]") {
  CHECK(errorOf("a: 1\nb: [1, 2]\nc: x\nd: {n: hello}\n").empty());
  CHECK(errorOf("a: -1\n") == "in.yaml:1: key 'a': expected a number > 0 m, found -1");
  CHECK(errorOf("a: 1\nzz: 3\n").find("in.yaml:2: key 'zz': unknown key") == 0);
  CHECK(errorOf("b: [1, 2]\n").find("missing required key 'a'") != std::string::npos);
  CHECK(errorOf("a: 1\nb: [1]\n") == "in.yaml:2: key 'b': expected at least 2 items, found 1");
  CHECK(errorOf("a: 1\nb: [1, 2.5]\n") == "in.yaml:2: key 'b[1]': expected an integer, found 2.5");
  CHECK(errorOf("a: 1\nc: z\n") == "in.yaml:2: key 'c': expected one of x, y; found z");
  CHECK(errorOf("a: 1\nd: {n: [1]}\n").find("key 'd.n': expected a string") != std::string::npos);
  CHECK(errorOf("a: \"1\"\n").find("expected a number, found \"1\"") != std::string::npos);
  // A oneOf of scalars names every alternative; one with a mapping branch, the scalar one's.
  CHECK(errorOf("a: 1\ne: auto\nf: {n: x}\n").empty());
  CHECK(errorOf("a: 1\ne: automatic\n") ==
        "in.yaml:2: key 'e': expected a number > 0 or 'auto'; found automatic");
  CHECK(errorOf("a: 1\ne: -2\n") == "in.yaml:2: key 'e': expected a number > 0 or 'auto'; found -2");
  CHECK(errorOf("a: 1\nf: sphere\n") == "in.yaml:2: key 'f': expected one of same, plane; found sphere");
}

TEST_CASE("unsupported schema keywords are rejected when the schema is loaded", "[schema]") {
  CHECK_THROWS_AS(JsonSchema(R"({"type": "object", "patternProperties": {}})", "x"),
                  std::invalid_argument);
}

TEST_CASE("body files: geometry discriminator and semantic checks", "[schema][body]") {
  const std::string head =
      "name: t\nmodel: axisymmetric\n"
      "material: {youngs_modulus: 2.11e11, poisson_ratio: 0.3, density: 7850}\n";
  auto err = [&](const std::string& tail) {
    try {
      parseBodyConfig(parseYamlText(head + tail, "body.yaml"));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(err("geometry: {type: half_disk, radius: 0.01}\nrefinement: {elevate_degree: [2, 2]}\n")
            .empty());
  CHECK(err("geometry: {type: cube, radius: 0.01}\n") ==
        "body.yaml:4: key 'geometry.type': expected one of half_disk, sphere, rod, nurbs; "
        "found cube");
  CHECK(err("geometry: {type: half_disk, radius: -0.01}\n") ==
        "body.yaml:4: key 'geometry.radius': expected a number > 0 m, found -0.01");
  CHECK(err("geometry: {type: sphere, radius: 0.01}\n").find("key 'model'") != std::string::npos);
  CHECK(err("geometry: {type: half_disk, radius: 0.01}\nrefinement: {insert_knots: [1]}\n")
            .find("body.yaml:5: key 'refinement.insert_knots': expected one entry per "
                  "parametric direction (2), found 1") == 0);
  const std::string nurbs =
      "geometry:\n  type: nurbs\n  degrees: [1, 1]\n"
      "  knots: [[0, 0, 1, 1], [0, 0, 1, 1]]\n"
      "  control_points: [[0, 0], [1, 0], [0, 1], [1, 1]]\n";
  CHECK(err(nurbs + "  weights: [1, 1, 1, 1]\n") == "");
  CHECK(err(nurbs + "  weights: [1, 1, 1]\n") ==
        "body.yaml:9: key 'geometry.weights': expected one weight per control point (4), found 3");
  const std::string decreasing =
      "geometry:\n  type: nurbs\n  degrees: [1, 1]\n"
      "  knots: [[0, 0, 1, 1], [0, 0, 0.7, 0.3, 1, 1]]\n"
      "  control_points: [[0, 0], [1, 0], [0, 1], [1, 1]]\n  weights: [1, 1, 1, 1]\n";
  CHECK(err(decreasing).find("body.yaml:7: key 'geometry.knots[1]': knot 3 (0.3) is smaller") == 0);
}
