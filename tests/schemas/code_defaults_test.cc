// Each default stated once: where a C++ struct still carries a default for a key that its
// schema also gives one (for programmatic users and for blocks a file may leave out, such
// as a body file without `reduction`), the two must agree. The programs read every such key
// from the document that JsonSchema::applyDefaults completed, so a disagreement would make a
// scene read from a file and one built in code differ without anyone noticing.
#include <string>

#include <catch2/catch.hpp>
#include <yaml-cpp/yaml.h>

#include "common/input/schemas.h"
#include "preproc/input/body_config.h"
#include "preproc/input/visualisation_config.h"
#include "runtime/contact/contact_pair.h"
#include "runtime/integration/bdf_integrator.h"
#include "runtime/output/result_writer.h"
#include "runtime/output/visualisation_frames.h"
#include "runtime/scene/initial_state.h"
#include "runtime/simulation/simulation.h"

using namespace ffriga;

namespace {

// The schema node at a local reference "#/$defs/NAME" (or the node itself).
YAML::Node resolved(const YAML::Node& root, YAML::Node node) {
  while (node.IsMap() && node["$ref"]) {
    const std::string ref = node["$ref"].Scalar();
    REQUIRE(ref.rfind("#/$defs/", 0) == 0);
    node = root["$defs"][ref.substr(8)];
  }
  return node;
}

// The `default` of the property at `path` ("integrator.rtol"; "[]" steps into a list's
// items: "bodies[].frozen"), read from the schema text the programs embed.
YAML::Node schemaDefault(const char* schemaText, const std::string& path) {
  const YAML::Node root = YAML::Load(schemaText);
  YAML::Node node = root;
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t dot = path.find('.', start);
    std::string part = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    const bool items = part.size() > 2 && part.compare(part.size() - 2, 2, "[]") == 0;
    if (items) part.resize(part.size() - 2);
    YAML::Node property = resolved(root, node)["properties"][part];
    INFO(path << ": no property '" << part << "'");
    REQUIRE(property.IsDefined());
    if (dot == std::string::npos) {
      if (property["default"]) return property["default"];
      return resolved(root, property)["default"];
    }
    node = items ? resolved(root, property)["items"] : property;
    start = dot + 1;
  }
  return YAML::Node();
}

template <class T>
T defaultOf(const char* schema, const std::string& path) {
  const YAML::Node d = schemaDefault(schema, path);
  INFO(path << " has no default in its schema");
  REQUIRE(d.IsDefined());
  return d.as<T>();
}

}  // namespace

TEST_CASE("code defaults: the scene's structs agree with scene.schema.json", "[schema][defaults]") {
  const IntegratorOptions integrator;
  CHECK(integrator.rtol == defaultOf<double>(kSceneSchema, "integrator.rtol"));
  CHECK(integrator.max_order == defaultOf<int>(kSceneSchema, "integrator.max_order"));
  LinearSolverKind solver = LinearSolverKind::kSundialsDense;
  REQUIRE(parseKind(defaultOf<std::string>(kSceneSchema, "integrator.linear_solver"), &solver));
  CHECK(solver == integrator.linear_solver);
  const AbsoluteTolerances atol;
  CHECK(atol.position == defaultOf<double>(kSceneSchema, "integrator.atol_position"));
  CHECK(atol.velocity == defaultOf<double>(kSceneSchema, "integrator.atol_velocity"));
  CHECK(atol.rotation == defaultOf<double>(kSceneSchema, "integrator.atol_rotation"));
  CHECK(atol.angular_velocity ==
        defaultOf<double>(kSceneSchema, "integrator.atol_angular_velocity"));
  const FlushConfig flush;
  CHECK(flush.rows == defaultOf<int>(kSceneSchema, "outputs.flush_rows"));
  CHECK(flush.interval == defaultOf<double>(kSceneSchema, "outputs.flush_interval"));
  CHECK(SimulationConfig().progress_interval ==
        defaultOf<double>(kSceneSchema, "outputs.progress_interval"));
  const VisualisationFramesConfig v;
  CHECK(v.magnification == defaultOf<double>(kSceneSchema, "outputs.visualisation.magnification"));
  CHECK(v.revolve == defaultOf<int>(kSceneSchema, "outputs.visualisation.revolve"));
  CHECK(ContactOptions().both_roles == defaultOf<bool>(kSceneSchema, "contacts[].both_roles"));
}

TEST_CASE("code defaults: the body's structs agree with body.schema.json", "[schema][defaults]") {
  const ReductionConfig r;
  ReductionMethod method = ReductionMethod::kRigid;
  REQUIRE(parseKind(defaultOf<std::string>(kBodySchema, "reduction.method"), &method));
  CHECK(method == r.method);
  FrameKind frame = FrameKind::kCentreOfMassGiven;
  REQUIRE(parseKind(defaultOf<std::string>(kBodySchema, "reduction.frame"), &frame));
  CHECK(frame == r.frame);
  CHECK(r.normal_modes == defaultOf<int>(kBodySchema, "reduction.normal_modes"));
  const PressurePatchConfig& pp = r.pressure_patches;
  CHECK(pp.radii == defaultOf<int>(kBodySchema, "reduction.pressure_patches.radii"));
  CHECK(pp.degree == defaultOf<int>(kBodySchema, "reduction.pressure_patches.degree"));
  CHECK(pp.tangential == defaultOf<bool>(kBodySchema, "reduction.pressure_patches.tangential"));
  CHECK(ContactConfig().name == defaultOf<std::string>(kBodySchema, "contact.name"));
  CHECK(MarkerConfig().interface == defaultOf<bool>(kBodySchema, "markers[].interface"));
  CHECK(StressLineConfig().points ==
        defaultOf<int>(kBodySchema, "visualisation.stress_lines[].points"));
}

TEST_CASE("code defaults: the lookup finds defaults and refuses what is not there",
          "[schema][defaults]") {
  // The helper itself: a default behind a list's items and one beside a $ref are found; a
  // key without a default gives an undefined node (so the checks above cannot pass vacuously).
  CHECK(schemaDefault(kSceneSchema, "bodies[].position").IsSequence());
  CHECK(schemaDefault(kSceneSchema, "bodies[].orientation")[0].as<double>() == 1.0);
  CHECK(!schemaDefault(kSceneSchema, "integrator.end_time").IsDefined());
  CHECK(!schemaDefault(kBodySchema, "material.density").IsDefined());
}
