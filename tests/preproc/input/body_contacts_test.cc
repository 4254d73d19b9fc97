// Several named contact regions per body (issue 27): the list form `contacts` and the short
// form `contact` read into BodyConfig::contacts with the key each came from, errors naming
// that key, and igaprep's pipeline writing one contact surface per region with the union
// of their control points as the Craig-Bampton interface.
#include <catch2/catch.hpp>

#include <cstdio>
#include <string>

#include "common/sid/sid_file.h"
#include "preproc/body_preprocessor.h"
#include "preproc/input/body_config.h"

namespace ffriga {
namespace {

// A small axisymmetric sphere (p = 3, q = 2, 8 x 8 spans of 0.125: a few hundred DOFs, so
// the pipeline runs in milliseconds); `contacts` is appended.
std::string smallSphere(const std::string& contacts) {
  return "name: small\n"
         "model: axisymmetric\n"
         "material: {youngs_modulus: 2.11e11, poisson_ratio: 0.3, density: 7850}\n"
         "geometry: {type: half_disk, radius: 0.01}\n"
         "refinement: {elevate_degree: [1, 1], insert_knots: [7, 7]}\n"
         "reduction: {normal_modes: 4}\n"
         "visualisation: {subdivisions: 0}\n" +
         contacts;
}

const char* const kPoles =
    "contacts:\n"
    "  - {name: top, face: eta_max, region: [[0.0, 0.25]]}\n"
    "  - {name: bottom, face: eta_min, region: [[0.0, 0.25]]}\n";

BodyConfig parsed(const std::string& yaml) {
  return parseBodyConfig(parseYamlText(yaml, "small.yaml"));
}

// The pipeline's interface size (distinct control points after tying) for a body file.
int interfacePoints(const std::string& contacts) {
  PreprocessSummary summary;
  preprocessBody(parsed(smallSphere(contacts)), {}, &summary);
  return summary.interface_control_points;
}

TEST_CASE("contacts: the list form gives one named region per entry, with its key",
          "[contact][body]") {
  const BodyConfig c = parsed(smallSphere(kPoles));
  REQUIRE(c.contacts.size() == 2);
  CHECK(c.contacts[0].name == "top");
  CHECK(c.contacts[0].key == "contacts[0]");
  CHECK(c.contacts[0].item == 0);
  CHECK(c.contacts[0].direction == 1);
  CHECK(c.contacts[0].upper);
  CHECK(c.contacts[1].name == "bottom");
  CHECK(c.contacts[1].key == "contacts[1]");
  CHECK(c.contacts[1].item == 1);
  CHECK(c.contacts[1].direction == 1);
  CHECK_FALSE(c.contacts[1].upper);
  REQUIRE(c.contacts[1].bounds.size() == 1);
  CHECK(c.contacts[1].bounds[0][0] == 0.0);  // values as written: exact
  CHECK(c.contacts[1].bounds[0][1] == 0.25);
}

TEST_CASE("contacts: the short form gives one region, named 'contact' by default",
          "[contact][body]") {
  const BodyConfig c = parsed(smallSphere("contact: {face: eta_max, region: [[0.0, 0.25]]}\n"));
  REQUIRE(c.contacts.size() == 1);
  CHECK(c.contacts[0].name == "contact");
  CHECK(c.contacts[0].key == "contact");
  CHECK(c.contacts[0].item == -1);
  std::string none = smallSphere("");  // no region: modal (Craig-Bampton needs an interface)
  none.insert(none.find("normal_modes"), "method: modal, ");
  CHECK(parsed(none).contacts.empty());
}

TEST_CASE("contacts: errors name the region's key and line", "[contact][body]") {
  // The second region's bound lies outside the knot range.
  CHECK_THROWS_WITH(
      parsed(smallSphere("contacts:\n"
                         "  - {name: top, face: eta_max, region: [[0.0, 0.25]]}\n"
                         "  - {name: b, face: eta_min, region: [[0.5, 1.5]]}\n")),
      Catch::Contains("small.yaml:10: key 'contacts[1].region[0]': expected lo < hi"));
  // Touching regions on one face are fine; overlapping ones are not.
  CHECK_NOTHROW(
      parsed(smallSphere("contacts:\n"
                         "  - {name: a, face: eta_max, region: [[0.0, 0.25]]}\n"
                         "  - {name: b, face: eta_max, region: [[0.25, 0.5]]}\n")));
  CHECK_THROWS_WITH(
      parsed(smallSphere("contacts:\n"
                         "  - {name: a, face: eta_max, region: [[0.0, 0.25]]}\n"
                         "  - {name: b, face: eta_min, region: [[0.0, 0.25]]}\n"
                         "  - {name: c, face: eta_max, region: [[0.125, 0.5]]}\n")),
      Catch::Contains("key 'contacts[2].region': the region overlaps contacts[0] ('a')"));
  CHECK_THROWS_WITH(parsed(smallSphere("contacts:\n"
                                       "  - {name: a, face: eta_max, region: [[0.0, 0.25]]}\n"
                                       "  - {name: a, face: eta_min, region: [[0.0, 0.25]]}\n")),
                    Catch::Contains("key 'contacts[1].name': name 'a' is used twice"));
  CHECK_THROWS_WITH(parsed(smallSphere(std::string(kPoles) +
                                       "contact: {face: eta_max, region: [[0.5, 0.75]]}\n")),
                    Catch::Contains("key 'contacts': give either 'contact'"));
}

TEST_CASE("igaprep with two regions: one named surface each, the interface their union",
          "[contact][body][sid]") {
  PreprocessSummary summary;
  const FlexibleBodySid sid = preprocessBody(parsed(smallSphere(kPoles)), {}, &summary);
  REQUIRE(sid.surfaces.size() == 2);  // file order
  CHECK(sid.surfaces[0].name == "top");
  CHECK(sid.surfaces[1].name == "bottom");
  for (const ContactSurface& s : sid.surfaces) {
    INFO(s.name);
    CHECK(s.element_level.size() == 2);  // two spans of 0.125 in [0, 0.25]
    CHECK(s.collocation_points.rows() > 0);
  }
  CHECK(summary.interface_control_points ==
        interfacePoints("contacts: [{name: top, face: eta_max, region: [[0.0, 0.25]]}]\n") +
            interfacePoints("contacts: [{name: b, face: eta_min, region: [[0.0, 0.25]]}]\n"));
  // Touching regions share the control points over their common knot line: counted once,
  // the same interface as the one region that covers both.
  const int touching = interfacePoints(
      "contacts:\n"
      "  - {name: a, face: eta_max, region: [[0.0, 0.25]]}\n"
      "  - {name: b, face: eta_max, region: [[0.25, 0.5]]}\n");
  CHECK(touching == interfacePoints("contact: {face: eta_max, region: [[0.0, 0.5]]}\n"));
  CHECK(touching < 2 * interfacePoints("contact: {face: eta_max, region: [[0.0, 0.25]]}\n"));

  // The SID file keeps both (HDF5 lists its groups by name).
  const std::string path = "body_contacts_test.sid.h5";
  writeSid(sid, path);
  const FlexibleBodySid back = readSid(path);
  std::remove(path.c_str());
  REQUIRE(back.surfaces.size() == 2);
  CHECK(back.surfaces[0].name == "bottom");
  CHECK(back.surfaces[1].name == "top");
  CHECK(back.surfaces[1].functions == sid.surfaces[0].functions);
  CHECK(back.surfaces[0].functions == sid.surfaces[1].functions);
}

}  // namespace
}  // namespace ffriga
